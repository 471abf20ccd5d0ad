// Reading untrusted .vdb files without letting a corrupt one take the process down.
//
// OpenVDB 10 trusts sizes stored in the file and asserts on some inconsistencies: a single
// flipped byte can abort the process (assertion in DelayedLoadMetadata) and a corrupt header
// can make it allocate tens of gigabytes. So every file is first read once by a separate
// program, `lighthouse-vdb-probe`, with a capped address space; only if it reads the file
// cleanly does the caller read it.
//
// The probe is started with posix_spawn (fork and exec in one): it is a fresh process with
// its own TBB pool, never a copy of the caller. A fork without exec copies only the forking
// thread, so a child of a process with TBB workers that waits for a worker (freeing a tree
// runs a parallel_for) waits for ever; that hung `lighthouse import` once.
#pragma once

#include "vdb/grid_selection.h"

#include <cstddef>
#include <string>

namespace lh {

// The probe's interface: `lighthouse-vdb-probe FILE MEMORY_CAP_BYTES [lighting-volume]`. It
// sets RLIMIT_AS to the cap (or the hard limit, if lower), reads every grid of FILE (with
// `lighting-volume`, every grid but the MPI's: GridSelection::LightingVolume) and exits with
// one of these.
constexpr const char* kProbeLightingVolumeArgument = "lighting-volume";
constexpr const char* kVdbProbeName = "lighthouse-vdb-probe";
constexpr int kProbeRead = 0;         // every grid read cleanly
constexpr int kProbeUsage = 2;        // wrong arguments
constexpr int kProbeReadFailed = 3;   // OpenVDB threw while reading
constexpr int kProbeOutOfMemory = 4;  // an allocation failed under the cap
// A crash (OpenVDB's assertions abort) ends the probe with that signal.

// What a trial read showed.
enum class ProbeResult {
    Read,         // the probe read the file cleanly
    NotIsolated,  // no verdict (the probe is missing, could not be started, gave no known
                  // exit code, or did not finish in time): the caller reads the file
                  // in-process, as it would without the probe
};

// Throws FileError naming `path` if the trial read crashes, runs out of its memory cap, or
// fails. Costs one extra read of the file, in a process started for it. `memoryCapBytes`
// = 0 picks 256x the file size, clamped to [2 GiB, half the physical memory]. `timeoutSeconds`
// = 0 picks 60 s plus 1 s per 10 MB of file; a probe still reading then is killed (NotIsolated).
//
// The probe is looked up beside the running executable (core/sibling_executable.h), where the
// build puts it next to `lighthouse` (and a symlink to it next to the test programs). If it
// is missing or cannot be started, the file is read in-process with no isolation, after one
// `warning:` line on stderr per process: a broken installation then still reads good files,
// as before the probe existed, and says why a corrupt one could crash it.
// `which`: the grids the caller will read; the probe reads those.
ProbeResult probeVdbReadable(const std::string& path, std::size_t memoryCapBytes = 0,
                             double timeoutSeconds = 0, GridSelection which = GridSelection::Every);

}  // namespace lh
