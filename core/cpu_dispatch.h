// Hot functions compiled twice, for x86-64-v3 (AVX2 and FMA: x86 CPUs since 2013) and for the
// baseline x86-64 that Debian builds for; the loader picks the version for the CPU it runs on
// (GCC function multi-versioning, an ifunc). Answers of the versions differ only by rounding
// (FMA). The marcher (LH_PER_CPU_FLATTENED) also has an x86-64-v4 version (AVX-512: 32
// vector registers for the one large function it is): 1-4.5% less time in paired runs
// (docs/performance.md). valgrind hides AVX-512, so callgrind counts the v3 one.
// Elsewhere (other compilers, other architectures) the macros are empty.
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define LH_PER_CPU __attribute__((target_clones("arch=x86-64-v3", "default")))
// The same, with every call inside inlined into each version (a loop's callees would otherwise
// run their baseline code from the x86-64-v3 version).
#define LH_PER_CPU_FLATTENED \
    __attribute__((flatten, target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define LH_PER_CPU
#define LH_PER_CPU_FLATTENED
#endif
