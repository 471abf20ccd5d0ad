#include "core/sibling_executable.h"

#include <unistd.h>

namespace lh {

SiblingExecutable findSiblingExecutable(const std::string& name) {
    SiblingExecutable s;
    std::error_code ec;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) {
        s.self = "this executable";
        return s;
    }
    s.self = self.string();
    s.path = self.parent_path() / name;
    s.found = ::access(s.path.c_str(), X_OK) == 0;
    return s;
}

}  // namespace lh
