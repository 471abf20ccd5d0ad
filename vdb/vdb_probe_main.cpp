// lighthouse-vdb-probe FILE MEMORY_CAP_BYTES [lighting-volume]
//
// The trial read of an untrusted .vdb file (vdb/safe_read.h), as a program of its own so that
// the caller starts it with exec and it never inherits the caller's threads. It caps its
// address space, reads every grid (or, with `lighting-volume`, the grids the caller will read:
// vdb/grid_selection.h) and answers with its exit code; what went wrong is also printed on
// stderr for a person running it by hand (the caller discards it).
#include "vdb/grid_selection.h"
#include "vdb/safe_read.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <sys/resource.h>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <new>

namespace {

// The cap in bytes; 0 if `text` is not a positive whole number.
rlim_t parseCap(const char* text) {
    if (*text < '0' || *text > '9') return 0;
    char* end = nullptr;
    errno = 0;
    const unsigned long long v = std::strtoull(text, &end, 10);
    if (errno != 0 || *end != '\0') return 0;
    return rlim_t(v);
}

// Lowers the soft address-space limit to `cap` (or to the hard limit, which an unprivileged
// process cannot raise).
bool capAddressSpace(rlim_t cap) {
    rlimit limit{};
    if (::getrlimit(RLIMIT_AS, &limit) != 0) return false;
    if (limit.rlim_max != RLIM_INFINITY && cap > limit.rlim_max) cap = limit.rlim_max;
    limit.rlim_cur = cap;
    return ::setrlimit(RLIMIT_AS, &limit) == 0;
}

}  // namespace

int main(int argc, char** argv) {
    const bool lightingVolumeOnly =
        argc == 4 && std::strcmp(argv[3], lh::kProbeLightingVolumeArgument) == 0;
    const rlim_t cap = argc == 3 || lightingVolumeOnly ? parseCap(argv[2]) : 0;
    if (cap == 0) {
        std::cerr << "usage: " << lh::kVdbProbeName << " FILE MEMORY_CAP_BYTES ["
                  << lh::kProbeLightingVolumeArgument << "]\n"
                  << "Reads every grid of FILE (or all but the MPI's planes) under the "
                     "address-space cap; exit code "
                  << lh::kProbeRead << " read, " << lh::kProbeReadFailed << " unreadable, "
                  << lh::kProbeOutOfMemory << " over the cap, " << lh::kProbeUsage << " usage.\n";
        return lh::kProbeUsage;
    }
    if (!capAddressSpace(cap)) {
        std::cerr << lh::kVdbProbeName << ": cannot cap the address space\n";
        return lh::kProbeUsage;
    }
    try {
        openvdb::initialize();
        openvdb::io::File file(argv[1]);
        file.open(/*delayLoad=*/false);
        lh::readSelectedGrids(file, lightingVolumeOnly ? lh::GridSelection::LightingVolume
                                                       : lh::GridSelection::Every);
        file.close();
        return lh::kProbeRead;
    } catch (const std::bad_alloc&) {
        std::cerr << argv[1] << ": out of memory under a cap of " << cap << " bytes\n";
        return lh::kProbeOutOfMemory;
    } catch (const std::exception& e) {
        std::cerr << argv[1] << ": " << e.what() << "\n";
        return lh::kProbeReadFailed;
    } catch (...) {
        std::cerr << argv[1] << ": unreadable\n";
        return lh::kProbeReadFailed;
    }
}
