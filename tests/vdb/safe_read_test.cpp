// The trial read of a .vdb file by lighthouse-vdb-probe (vdb/safe_read.h): a verdict on good
// and corrupt files, no verdict (instead of a hang) from a probe past its deadline, the probe's
// exit codes, and that the child really is the probe (exec'd, not a fork of this process).
#include "vdb/safe_read.h"

#include "core/errors.h"
#include "core/sibling_executable.h"
#include "tests/support/cut_mpi_file.h"
#include "vdb/example_volume.h"
#include "vdb/volume_io.h"

#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <thread>
#include <vector>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace lh {
namespace {

std::string exampleFile() {
    static const std::string path = [] {
        const std::filesystem::path dir = std::filesystem::temp_directory_path() / "lh_safe_read";
        std::filesystem::create_directories(dir);
        const std::string p = (dir / ("example_" + std::to_string(::getpid()) + ".vdb")).string();
        saveVolume(p, makeExampleVolume(3, 32));
        return p;
    }();
    return path;
}

std::string corruptFile() {
    static const std::string path = [] {
        const std::string p = (std::filesystem::temp_directory_path() / "lh_safe_read" /
                               ("corrupt_" + std::to_string(::getpid()) + ".vdb"))
                                  .string();
        std::ifstream in(exampleFile(), std::ios::binary);
        std::string bytes(std::istreambuf_iterator<char>(in), {});
        bytes.resize(bytes.size() / 2);  // truncated in the middle of its grids
        std::ofstream(p, std::ios::binary) << bytes;
        return p;
    }();
    return path;
}

// A valid file whose one string metadata claims to be 2 GiB long: reading it allocates that
// much, which fails under the probe's cap.
std::string hugeSizeFile() {
    static const std::string path = [] {
        const std::string p = (std::filesystem::temp_directory_path() / "lh_safe_read" /
                               ("huge_" + std::to_string(::getpid()) + ".vdb"))
                                  .string();
        openvdb::initialize();
        auto grid = openvdb::FloatGrid::create();
        grid->tree().setValueOn(openvdb::Coord(1, 2, 3), 1.f);
        openvdb::MetaMap meta;
        const std::string marker = "MARKER_OF_A_STRING_METADATA";
        meta.insertMeta("note", openvdb::StringMetadata(marker));
        openvdb::io::File(p).write({grid}, meta);
        std::ifstream in(p, std::ios::binary);
        std::string bytes(std::istreambuf_iterator<char>(in), {});
        const std::size_t at = bytes.find(marker);
        EXPECT_NE(at, std::string::npos);
        EXPECT_GE(at, 4u);
        const std::uint32_t length = 0x7ffffff0u;  // little-endian, as OpenVDB writes it
        std::memcpy(&bytes[at - 4], &length, 4);
        std::ofstream(p, std::ios::binary) << bytes;
        return p;
    }();
    return path;
}

std::filesystem::path probeBinary() {
    const SiblingExecutable probe = findSiblingExecutable(kVdbProbeName);
    EXPECT_TRUE(probe.found) << kVdbProbeName << " is not beside " << probe.self;
    return probe.path;
}

// Runs the probe by hand (its output discarded) and returns its exit code.
int probeExitCode(const std::vector<std::string>& args) {
    std::string command = "'" + probeBinary().string() + "'";
    for (const auto& a : args) command += " '" + a + "'";
    const int status = std::system((command + " >/dev/null 2>&1").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(SafeRead, AGoodFileIsReadInTheChild) {
    EXPECT_EQ(probeVdbReadable(exampleFile()), ProbeResult::Read);
}

TEST(SafeRead, ACorruptFileIsAClearErrorFromTheProbe) {
    try {
        probeVdbReadable(corruptFile());
        ADD_FAILURE() << "a truncated file passed the trial read";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("is not a readable VDB file"), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find(corruptFile()), std::string::npos) << e.what();
    }
}

TEST(SafeRead, ACorruptSizeIsCaughtByTheMemoryCap) {
    try {
        probeVdbReadable(hugeSizeFile(), std::size_t(1) << 30);
        ADD_FAILURE() << "a 2 GiB string read under a 1 GiB cap";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("would need more than 1 GiB: its sizes are corrupt"),
                  std::string::npos)
            << e.what();
    }
}

TEST(SafeRead, TheProbesExitCodesSayWhatHappened) {
    const std::string cap = std::to_string(std::size_t(2) << 30);
    EXPECT_EQ(probeExitCode({exampleFile(), cap}), kProbeRead);
    EXPECT_EQ(probeExitCode({corruptFile(), cap}), kProbeReadFailed);
    EXPECT_EQ(probeExitCode({"/no/such/file.vdb", cap}), kProbeReadFailed);
    EXPECT_EQ(probeExitCode({hugeSizeFile(), cap}), kProbeOutOfMemory);
    EXPECT_EQ(probeExitCode({exampleFile()}), kProbeUsage);                 // no cap
    EXPECT_EQ(probeExitCode({exampleFile(), "0"}), kProbeUsage);            // not positive
    EXPECT_EQ(probeExitCode({exampleFile(), "2GiB"}), kProbeUsage);         // not a number of bytes
    EXPECT_EQ(probeExitCode({exampleFile(), cap, "volume"}), kProbeUsage);  // unknown selection
}

// With `lighting-volume` the probe reads what loadVolume reads: every grid but the MPI's. A file
// cut short inside its MPI (saveVdb writes the MPI's planes last) fails the whole read and
// passes that one.
TEST(SafeRead, TheProbeReadsOnlyTheGridsItsCallerWill) {
    const std::string path = (std::filesystem::temp_directory_path() / "lh_safe_read" /
                              ("cut_mpi_" + std::to_string(::getpid()) + ".vdb"))
                                 .string();
    test::saveWithFilledMpi(path, makeExampleVolume(2, 8));
    test::cutShortInsideItsMpi(path);
    const std::string cap = std::to_string(std::size_t(2) << 30);
    EXPECT_EQ(probeExitCode({path, cap}), kProbeReadFailed);
    EXPECT_EQ(probeExitCode({path, cap, kProbeLightingVolumeArgument}), kProbeRead);
    EXPECT_EQ(probeVdbReadable(path, 0, 0, GridSelection::LightingVolume), ProbeResult::Read);
    EXPECT_THROW(probeVdbReadable(path), FileError);
}

// The probe's child is the probe binary itself (its /proc/PID/exe), not a copy of this test
// process: a fork without exec would show this test's executable there. The probe is held
// on a FIFO (its open blocks until a writer comes) while the child is inspected.
TEST(SafeRead, TheChildIsTheProbeProgramNotAForkOfTheCaller) {
    const std::filesystem::path fifo = std::filesystem::temp_directory_path() /
                                       ("lh_safe_read_exe_fifo_" + std::to_string(::getpid()));
    std::filesystem::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    auto verdict =
        std::async(std::launch::async, [&] { return probeVdbReadable(fifo.string(), 0, 10.0); });
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe");
    const std::filesystem::path expected = std::filesystem::canonical(probeBinary());
    std::string seen;
    pid_t child = -1;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(8);
    while (seen != expected.string() && std::chrono::steady_clock::now() < until) {
        for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
            const std::string pid = entry.path().filename().string();
            if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
            std::ifstream stat(entry.path() / "stat");
            std::string line;
            std::getline(stat, line);
            const auto close = line.rfind(')');  // "pid (comm) state ppid ..."
            if (close == std::string::npos) continue;
            char state = 0;
            long ppid = 0;
            if (std::sscanf(line.c_str() + close + 1, " %c %ld", &state, &ppid) != 2 ||
                ppid != ::getpid())
                continue;
            std::error_code ec;
            const auto exe = std::filesystem::read_symlink(entry.path() / "exe", ec);
            if (!ec && exe != self)
                seen = exe.string(), child = pid_t(std::stol(pid));  // before exec: us
        }
        if (seen != expected.string()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    EXPECT_EQ(seen, expected.string()) << "no child of this process ran " << expected;
    if (child > 0) ::kill(child, SIGKILL);  // else the deadline ends it
    try {
        verdict.get();
    } catch (const FileError&) {
        // A killed probe reads as a crash: the verdict is not what this test is about.
    }
    std::filesystem::remove(fifo);
}

// A child still reading at its deadline is killed: the caller gets no verdict and reads the
// file itself, instead of waiting for ever. The child is made to wait for certain: the path is
// a FIFO nobody writes to, so its open() blocks until the kill. (A tiny deadline on a real
// file was a race: on CI the child sometimes finished the read first.)
TEST(SafeRead, AChildPastItsDeadlineIsKilledAndGivesNoVerdict) {
    const std::filesystem::path fifo = std::filesystem::temp_directory_path() /
                                       ("lh_safe_read_fifo_" + std::to_string(::getpid()));
    std::filesystem::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << "cannot make a FIFO in the temporary directory";
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(probeVdbReadable(fifo.string(), 0, 0.3), ProbeResult::NotIsolated);
    const double waited =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::filesystem::remove(fifo);
    EXPECT_GE(waited, 0.3) << "the probe gave up before its deadline";
    // The next trial read is unaffected.
    EXPECT_EQ(probeVdbReadable(exampleFile()), ProbeResult::Read);
}

// A child forked (without exec) from a process with TBB workers does not have them, and
// freeing the grids it read ran a parallel_for there that waited for ever (`lighthouse import`
// hung in CI). The probe is exec'd, with a pool of its own: with the parent's pool busy all
// along, every trial read must finish (a child that waits shows up as NotIsolated at the
// 20 s deadline).
TEST(SafeRead, TrialReadsFinishWhileTheParentsThreadPoolIsBusy) {
    std::atomic<bool> stop{false};
    std::thread busy([&] {
        while (!stop)
            tbb::parallel_for(0, 256, [](int) {
                volatile double x = 0;
                for (int i = 0; i < 20000; ++i) x = x + i;
            });
    });
    int read = 0;
    for (int i = 0; i < 20; ++i)
        read += probeVdbReadable(exampleFile(), 0, 20.0) == ProbeResult::Read;
    stop = true;
    busy.join();
    EXPECT_EQ(read, 20);
}

}  // namespace
}  // namespace lh
