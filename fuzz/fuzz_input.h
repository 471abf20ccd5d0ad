// What the fuzz targets share: the loaders take paths, so each input is written to a file
// first, in a folder of this process's own (libFuzzer's -fork and -jobs run several processes).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace lh::fuzz {

// Where the scratch folders go: /dev/shm (memory) when there is one. On a disk, ext4 starts
// writing a file back when it is truncated and rewritten, which made each input wait ~3 ms
// for the disk (266 inputs/s, 6% CPU, on the points target).
inline std::filesystem::path scratchRoot() {
    std::error_code ec;
    if (std::filesystem::is_directory("/dev/shm", ec) && ::access("/dev/shm", W_OK) == 0)
        return "/dev/shm";
    return std::filesystem::temp_directory_path();
}

// The process's folder, created on first use and removed when the process exits normally (a
// crash leaves it, with the input that crashed, for a look).
inline const std::filesystem::path& scratchDir() {
    struct Dir {
        std::filesystem::path path;
        Dir() : path(scratchRoot() / ("lighthouse-fuzz-" + std::to_string(::getpid()))) {
            std::filesystem::create_directories(path);
        }
        ~Dir() {
            std::error_code ec;
            std::filesystem::remove_all(path, ec);
        }
    };
    static const Dir dir;
    return dir.path;
}

// Writes the input to `name` in the scratch folder and returns its path.
inline std::string writeInput(const std::uint8_t* data, std::size_t size, const std::string& name) {
    const std::filesystem::path path = scratchDir() / name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    out.close();
    if (!out) {
        std::fprintf(stderr, "fuzz: cannot write the input to %s\n", path.c_str());
        std::abort();
    }
    return path.string();
}

// A broken promise of the code under test (not a refusal of a bad input): reported like a
// crash, so that the fuzzer keeps the input.
[[noreturn]] inline void fail(const std::string& what) {
    std::fprintf(stderr, "fuzz: %s\n", what.c_str());
    std::abort();
}

}  // namespace lh::fuzz
