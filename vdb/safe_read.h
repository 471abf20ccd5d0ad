// Reading untrusted .vdb files without letting a corrupt one take the process down.
//
// OpenVDB 10 trusts sizes stored in the file and asserts on some inconsistencies: a single
// flipped byte can abort the process (assertion in DelayedLoadMetadata) and a corrupt header
// can make it allocate tens of gigabytes. So every file is first read once in a forked child
// with a capped address space; only if the child reads it cleanly does the caller read it.
#pragma once

#include <string>

namespace lh {

// What a trial read showed.
enum class ProbeResult {
    Read,         // the child read the file cleanly
    NotIsolated,  // no verdict (the child could not be started, or did not finish in time):
                  // the caller reads the file in-process, as it would without the probe
};

// Throws FileError naming `path` if a trial read in a child process crashes, runs out of its
// memory cap, or fails. Costs one extra read of the file. `memoryCapBytes` = 0 picks 256x the
// file size, clamped to [2 GiB, half the physical memory]. `timeoutSeconds` = 0 picks 60 s
// plus 1 s per 10 MB of file; a child still reading then is killed (NotIsolated).
//
// The child is a fork of a process that may have TBB worker threads, which do not exist in
// the child: it never frees the grids it read (a tree's destructor runs a TBB parallel_for,
// which waited forever there for workers that are gone: `lighthouse import` hung in CI),
// leaving them to _exit. The deadline keeps any other such wait (in the read itself, say)
// from hanging the parent.
ProbeResult probeVdbReadable(const std::string& path, std::size_t memoryCapBytes = 0, double timeoutSeconds = 0);

}  // namespace lh
