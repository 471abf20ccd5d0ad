#include "core/path_guard.h"

#include "core/errors.h"

#include <filesystem>
#include <system_error>

namespace lh {

namespace fs = std::filesystem;

bool sameFile(const std::string& a, const std::string& b) {
    std::error_code ec;
    // equivalent() compares device and inode, so hard links and symlinks count as the same.
    const bool same = fs::equivalent(a, b, ec);
    return !ec && same;
}

namespace {

// Whether `path` (existing or not) lies inside the existing directory `dir`.
bool isInside(const fs::path& path, const fs::path& dir) {
    std::error_code ec;
    const fs::path d = fs::canonical(dir, ec);
    if (ec) return false;
    const fs::path p = fs::weakly_canonical(path, ec);
    if (ec) return false;
    auto pi = p.begin();
    for (auto di = d.begin(); di != d.end(); ++di, ++pi)
        if (pi == p.end() || *pi != *di) return false;
    return true;
}

}  // namespace

void requireOutputIsNotAnInput(const std::string& output, const std::string& outputOption,
                               const std::vector<NamedInput>& inputs) {
    std::error_code ec;
    const bool outputIsDirectory = fs::is_directory(output, ec);
    for (const NamedInput& input : inputs) {
        if (input.path.empty()) continue;
        std::string relation;
        if (sameFile(output, input.path))
            relation = "is the input given as ";
        else if (fs::is_directory(input.path, ec) && isInside(output, input.path))
            relation = "is inside the directory given as ";
        else if (outputIsDirectory && isInside(input.path, output))
            relation = "is a directory that holds the input given as ";  // replacing it would
                                                                         // delete the input
        if (relation.empty()) continue;
        throw InputError("output '" + output + "' (" + outputOption + ") " + relation +
                         input.option + " ('" + input.path +
                         "'), which it would overwrite; choose another output path");
    }
}

}  // namespace lh
