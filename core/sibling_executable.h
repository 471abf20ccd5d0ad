// Finding a program that ships beside the running one.
//
// `lighthouse` runs two helpers, `lighthouse-net` (the network's commands) and
// `lighthouse-vdb-probe` (the trial read of untrusted .vdb files). Both are built, and
// installed, in the same directory as the program that runs them, so they are looked up
// beside /proc/self/exe: no PATH search, so a build tree and an installed bin/ each run their
// own helpers.
#pragma once

#include <filesystem>
#include <string>

namespace lh {

struct SiblingExecutable {
    std::filesystem::path path;  // where it should be: beside the running executable
    std::string self;            // the running executable, or "this executable" if unknown
    bool found = false;          // `path` exists and may be executed
};

SiblingExecutable findSiblingExecutable(const std::string& name);

}  // namespace lh
