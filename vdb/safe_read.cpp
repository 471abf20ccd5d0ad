#include "vdb/safe_read.h"

#include "core/errors.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <optional>
#include <cstring>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace lh {

namespace {

// Child exit codes.
constexpr int kReadOk = 0;
constexpr int kReadFailed = 3;
constexpr int kOutOfMemory = 4;

std::size_t halfPhysicalMemory() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || pageSize <= 0) return std::size_t(8) << 30;
    return std::size_t(pages) * std::size_t(pageSize) / 2;
}

[[noreturn]] void childRead(const std::string& path, std::size_t cap) {
    // Quiet: the parent reports. A crash here only ends the child.
    const int devNull = ::open("/dev/null", O_WRONLY);
    if (devNull >= 0) ::dup2(devNull, STDERR_FILENO);
    rlimit limit{cap, cap};
    ::setrlimit(RLIMIT_AS, &limit);
    int code = kReadFailed;
    try {
        openvdb::initialize();
        openvdb::io::File file(path);
        file.open(false);
        const openvdb::GridPtrVecPtr grids = file.getGrids();
        // Exit with the grids alive: their destructors would run TBB (safe_read.h).
        ::_exit(kReadOk);
    } catch (const std::bad_alloc&) {
        code = kOutOfMemory;
    } catch (...) {
        code = kReadFailed;
    }
    ::_exit(code);
}

// The file's size in bytes; nullopt if it cannot be had.
std::optional<std::size_t> fileSize(const std::string& path) {
    std::error_code ec;
    const std::size_t bytes = std::filesystem::file_size(path, ec);
    if (ec) return std::nullopt;
    return bytes;
}

// Address-space cap of the trial read: 256 times the file size (Blosc rarely compresses
// voxel data beyond 10x), at least 2 GiB (libraries and thread stacks), at most half the RAM.
// A corrupt size field then fails in about a second instead of filling the machine.
std::size_t defaultCap(std::optional<std::size_t> bytes) {
    const std::size_t wanted = bytes ? *bytes * 256 : halfPhysicalMemory();
    return std::clamp(wanted, std::size_t(2) << 30, std::max(halfPhysicalMemory(), std::size_t(2) << 30));
}

// The trial read's deadline: a minute, and a second more per 10 MB of file.
double defaultTimeout(std::optional<std::size_t> bytes) { return 60.0 + (bytes ? double(*bytes) / 10e6 : 0.0); }

// Waits for the child until `timeoutSeconds`; false (the child killed and reaped) if it was
// still running then.
bool waitForChild(pid_t pid, double timeoutSeconds, int& status) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeoutSeconds);
    auto pause = std::chrono::microseconds(200);  // first reads take milliseconds; back off to 50 ms
    for (;;) {
        const pid_t done = ::waitpid(pid, &status, WNOHANG);
        if (done == pid) return true;
        if (done < 0 && errno != EINTR) return true;  // no such child: nothing to wait for
        if (std::chrono::steady_clock::now() >= deadline) break;
        std::this_thread::sleep_for(pause);
        pause = std::min(pause * 2, std::chrono::microseconds(50000));
    }
    ::kill(pid, SIGKILL);
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    return false;
}

}  // namespace

ProbeResult probeVdbReadable(const std::string& path, std::size_t memoryCapBytes, double timeoutSeconds) {
    const std::optional<std::size_t> bytes = fileSize(path);
    const std::size_t cap = memoryCapBytes ? memoryCapBytes : defaultCap(bytes);
    const double timeout = timeoutSeconds > 0 ? timeoutSeconds : defaultTimeout(bytes);
    std::fflush(nullptr);  // the child must not flush the parent's buffered output again
    const pid_t pid = ::fork();
    if (pid < 0) return ProbeResult::NotIsolated;  // cannot isolate: the caller reads in-process
    if (pid == 0) childRead(path, cap);
    int status = 0;
    if (!waitForChild(pid, timeout, status)) return ProbeResult::NotIsolated;
    if (WIFEXITED(status) && WEXITSTATUS(status) == kReadOk) return ProbeResult::Read;
    std::string why;
    if (WIFSIGNALED(status))
        why = "OpenVDB crashed reading it (" + std::string(::strsignal(WTERMSIG(status))) + ")";
    else if (WIFEXITED(status) && WEXITSTATUS(status) == kOutOfMemory)
        why = "reading it would need more than " + std::to_string(cap >> 30) +
              " GiB: its sizes are corrupt";
    else
        why = "OpenVDB cannot read it";
    throw FileError("'" + path + "' is not a readable VDB file: " + why + " (corrupt or truncated?)");
}

}  // namespace lh
