#include "vdb/safe_read.h"

#include "core/errors.h"
#include "core/sibling_executable.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <thread>

extern char** environ;

namespace lh {

namespace {

std::size_t halfPhysicalMemory() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || pageSize <= 0) return std::size_t(8) << 30;
    return std::size_t(pages) * std::size_t(pageSize) / 2;
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
    return std::clamp(wanted, std::size_t(2) << 30,
                      std::max(halfPhysicalMemory(), std::size_t(2) << 30));
}

// The trial read's deadline: a minute, and a second more per 10 MB of file.
double defaultTimeout(std::optional<std::size_t> bytes) {
    return 60.0 + (bytes ? double(*bytes) / 10e6 : 0.0);
}

// One line per process: every later read would repeat it.
void warnOnceThatReadsAreNotIsolated(const std::string& why) {
    static std::atomic<bool> warned{false};
    if (warned.exchange(true)) return;
    std::cerr
        << "warning: " << why
        << ": .vdb files are read without a trial read in a separate process, so a corrupt one may "
           "crash this program\n";
}

// Starts the probe on `path` with its output discarded (the parent reports); -1 and errno
// if it cannot be started.
pid_t spawnProbe(const std::filesystem::path& probe, const std::string& path, std::size_t cap,
                 GridSelection which) {
    posix_spawn_file_actions_t files;
    posix_spawnattr_t attr;
    ::posix_spawn_file_actions_init(&files);
    ::posix_spawn_file_actions_addopen(&files, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    ::posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    ::posix_spawn_file_actions_addopen(&files, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
    ::posix_spawnattr_init(&attr);
    // No signal the caller blocks or ignores carries over: the probe must die as it would alone.
    sigset_t none, all;
    sigemptyset(&none);
    sigfillset(&all);
    ::posix_spawnattr_setsigmask(&attr, &none);
    ::posix_spawnattr_setsigdefault(&attr, &all);
    ::posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    const std::string capText = std::to_string(cap);
    char* argv[] = {const_cast<char*>(probe.c_str()), const_cast<char*>(path.c_str()),
                    const_cast<char*>(capText.c_str()),
                    which == GridSelection::LightingVolume
                        ? const_cast<char*>(kProbeLightingVolumeArgument)
                        : nullptr,
                    nullptr};
    pid_t pid = -1;
    const int err = ::posix_spawn(&pid, probe.c_str(), &files, &attr, argv, environ);
    ::posix_spawnattr_destroy(&attr);
    ::posix_spawn_file_actions_destroy(&files);
    if (err != 0) {
        errno = err;
        return -1;
    }
    return pid;
}

// Waits for the child until `timeoutSeconds`; false (the child killed and reaped) if it was
// still running then.
bool waitForChild(pid_t pid, double timeoutSeconds, int& status) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(timeoutSeconds);
    auto pause =
        std::chrono::microseconds(200);  // first reads take milliseconds; back off to 50 ms
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

ProbeResult probeVdbReadable(const std::string& path, std::size_t memoryCapBytes,
                             double timeoutSeconds, GridSelection which) {
    const SiblingExecutable probe = findSiblingExecutable(kVdbProbeName);
    if (!probe.found) {
        warnOnceThatReadsAreNotIsolated(std::string(kVdbProbeName) + " was not found beside " +
                                        probe.self);
        return ProbeResult::NotIsolated;
    }
    const std::optional<std::size_t> bytes = fileSize(path);
    const std::size_t cap = memoryCapBytes ? memoryCapBytes : defaultCap(bytes);
    const double timeout = timeoutSeconds > 0 ? timeoutSeconds : defaultTimeout(bytes);
    const pid_t pid = spawnProbe(probe.path, path, cap, which);
    if (pid < 0) {
        warnOnceThatReadsAreNotIsolated("cannot start " + probe.path.string() + " (" +
                                        std::strerror(errno) + ")");
        return ProbeResult::NotIsolated;
    }
    int status = 0;
    if (!waitForChild(pid, timeout, status)) return ProbeResult::NotIsolated;
    std::string why;
    if (WIFSIGNALED(status)) {
        why = "OpenVDB crashed reading it (" + std::string(::strsignal(WTERMSIG(status))) + ")";
    } else if (WIFEXITED(status) && WEXITSTATUS(status) == kProbeRead) {
        return ProbeResult::Read;
    } else if (WIFEXITED(status) && WEXITSTATUS(status) == kProbeOutOfMemory) {
        why = "reading it would need more than " + std::to_string(cap >> 30) +
              " GiB: its sizes are corrupt";
    } else if (WIFEXITED(status) && WEXITSTATUS(status) == kProbeReadFailed) {
        why = "OpenVDB cannot read it";
    } else {
        // A probe of another version, or one that could not run: no verdict on the file.
        warnOnceThatReadsAreNotIsolated(
            probe.path.string() + " ended with exit code " +
            std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1));
        return ProbeResult::NotIsolated;
    }
    throw FileError("'" + path + "' is not a readable VDB file: " + why +
                    " (corrupt or truncated?)");
}

}  // namespace lh
