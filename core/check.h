// LH_DCHECK(condition): an invariant of a hot path, checked in debug builds and compiled out
// of release builds (NDEBUG), in the spirit of pbrt's DCHECK. A failed check is a bug in this
// code, never bad input (bad input gets an lh::Error): it prints the condition, the file and
// the line to stderr and aborts, so that a debug test run stops where the invariant broke.
#pragma once

#include <cstdio>
#include <cstdlib>

namespace lh::detail {

[[noreturn]] inline void checkFailed(const char* condition, const char* file, int line) {
    std::fprintf(stderr, "%s:%d: internal check failed: %s\n", file, line, condition);
    std::abort();
}

}  // namespace lh::detail

#ifndef NDEBUG
#define LH_DCHECK(condition) \
    ((condition) ? static_cast<void>(0) : ::lh::detail::checkFailed(#condition, __FILE__, __LINE__))
#else
// Not evaluated (no cost, no side effects), but still compiled, so that it cannot rot.
#define LH_DCHECK(condition) static_cast<void>(sizeof((condition) ? 1 : 0))
#endif
