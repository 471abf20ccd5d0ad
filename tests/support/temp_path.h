// A path in the system's temporary directory that no other test process uses at the same time:
// ctest runs every test case as its own process, two at a time, so fixed names would collide.
#pragma once

#include <filesystem>
#include <string>

#include <unistd.h>

namespace lh::test {

inline std::string uniqueTempPath(const std::string& name) {
    return (std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_" + name))
        .string();
}

}  // namespace lh::test
