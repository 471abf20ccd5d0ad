// Reading untrusted .vdb files without letting a corrupt one take the process down.
//
// OpenVDB 10 trusts sizes stored in the file and asserts on some inconsistencies: a single
// flipped byte can abort the process (assertion in DelayedLoadMetadata) and a corrupt header
// can make it allocate tens of gigabytes. So every file is first read once in a forked child
// with a capped address space; only if the child reads it cleanly does the caller read it.
#pragma once

#include <string>

namespace lh {

// Throws FileError naming `path` if a trial read in a child process crashes, runs out of its
// memory cap, or fails. Costs one extra read of the file. `memoryCapBytes` = 0 picks 256x the
// file size, clamped to [2 GiB, half the physical memory].
void probeVdbReadable(const std::string& path, std::size_t memoryCapBytes = 0);

}  // namespace lh
