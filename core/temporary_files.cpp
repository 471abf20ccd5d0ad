#include "core/temporary_files.h"

#include <unistd.h>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <regex>
#include <set>
#include <system_error>
#include <vector>

namespace lh {

namespace fs = std::filesystem;

namespace {

// Whether process `pid` runs on this machine. EPERM: it runs, as another user. A zombie (a
// killed process whose parent has not yet reaped it) writes nothing more: it does not run.
bool processRuns(long pid) {
    if (pid <= 0 || (::kill(pid_t(pid), 0) != 0 && errno != EPERM)) return false;
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string text;
    std::getline(stat, text);
    const std::size_t close = text.rfind(')');  // "PID (COMMAND) STATE ...": COMMAND may hold ')'
    return !(close != std::string::npos && close + 2 < text.size() &&
             (text[close + 2] == 'Z' || text[close + 2] == 'X'));
}

}  // namespace

const std::string& thisHostTag() {
    static const std::string tag = [] {
        char name[256] = {};
        if (::gethostname(name, sizeof name - 1) != 0) name[0] = '\0';
        std::uint32_t hash = 2166136261u;  // 32-bit FNV-1a
        for (const char* c = name; *c; ++c) hash = (hash ^ std::uint8_t(*c)) * 16777619u;
        char hex[9];
        std::snprintf(hex, sizeof hex, "%08x", unsigned(hash));
        return std::string(hex);
    }();
    return tag;
}

std::string temporaryBeside(const std::string& finalPath, const std::string& kind,
                            bool keepExtension) {
    static std::atomic<unsigned> counter{0};
    const fs::path p(finalPath);
    std::string stem = keepExtension ? p.stem().string() : p.filename().string();
    std::string ext = keepExtension ? p.extension().string() : std::string();
    const std::string tag = "." + kind + std::to_string(::getpid()) + "_" +
                            std::to_string(counter++) + "_" + thisHostTag();
    if (1 + tag.size() + ext.size() > kMaxFileNameBytes)
        ext.clear();  // longer than any format's extension
    // A file name holds at most kMaxFileNameBytes bytes: shorten the stem, so that an output
    // name near the limit still gets a temporary.
    const std::size_t fixed = 1 + tag.size() + ext.size();
    if (fixed + stem.size() > kMaxFileNameBytes) stem.resize(kMaxFileNameBytes - fixed);
    return (p.parent_path() / ("." + stem + tag + ext)).string();
}

std::optional<TemporaryOwner> temporaryOwner(const std::string& fileName) {
    // ".STEM.KIND<pid>_<n>_<host>EXT", as temporaryBeside writes it.
    static const std::regex pattern(
        R"(^\..*\.(tmp|old)([0-9]{1,9})_[0-9]{1,10}_([0-9a-f]{8})(\.[^.]*)?$)");
    std::smatch m;
    if (!std::regex_match(fileName, m, pattern)) return std::nullopt;
    return TemporaryOwner{std::stol(m[2].str()), m[3].str()};
}

void removeAbandonedTemporaries(const std::string& folder) {
    const fs::path dir = folder.empty() ? fs::path(".") : fs::path(folder);
    std::error_code ec;
    fs::directory_iterator it(dir, ec);
    if (ec) return;  // no folder (yet): nothing to remove, and the next call looks again
    {
        static std::mutex mutex;
        static std::set<std::string> swept;
        const std::lock_guard<std::mutex> lock(mutex);
        if (!swept.insert(fs::absolute(dir, ec).lexically_normal().string()).second) return;
    }
    std::vector<fs::path> abandoned;
    for (const fs::directory_iterator end; it != end; it.increment(ec)) {
        if (ec) break;
        const std::string name = it->path().filename().string();
        if (name.empty() || name[0] != '.') continue;  // a quick test before the pattern
        const std::optional<TemporaryOwner> owner = temporaryOwner(name);
        if (owner && owner->host == thisHostTag() && !processRuns(owner->pid))
            abandoned.push_back(it->path());
    }
    for (const fs::path& path : abandoned) {
        std::error_code ignored;
        fs::remove_all(path, ignored);  // a symbolic link is removed, never followed
    }
}

}  // namespace lh
