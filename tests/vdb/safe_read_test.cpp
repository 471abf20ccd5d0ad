// The trial read of a .vdb file in a child process (vdb/safe_read.h): a verdict on good
// files, no verdict (instead of a hang) from a child past its deadline, and trial reads that
// finish while the parent's TBB pool is busy.
#include "vdb/safe_read.h"

#include "vdb/example_volume.h"
#include "vdb/volume_io.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <thread>

#include <sys/stat.h>
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

TEST(SafeRead, AGoodFileIsReadInTheChild) {
    EXPECT_EQ(probeVdbReadable(exampleFile()), ProbeResult::Read);
}

// A child still reading at its deadline is killed: the caller gets no verdict and reads the
// file itself, instead of waiting for ever. The child is made to wait for certain: the path is
// a FIFO nobody writes to, so its open() blocks until the kill. (A tiny deadline on a real
// file was a race: on CI the child sometimes finished the read first.)
TEST(SafeRead, AChildPastItsDeadlineIsKilledAndGivesNoVerdict) {
    const std::filesystem::path fifo =
        std::filesystem::temp_directory_path() / ("lh_safe_read_fifo_" + std::to_string(::getpid()));
    std::filesystem::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << "cannot make a FIFO in the temporary directory";
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(probeVdbReadable(fifo.string(), 0, 0.3), ProbeResult::NotIsolated);
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::filesystem::remove(fifo);
    EXPECT_GE(waited, 0.3) << "the probe gave up before its deadline";
    // The next trial read is unaffected.
    EXPECT_EQ(probeVdbReadable(exampleFile()), ProbeResult::Read);
}

// The child is a fork of a process whose TBB workers it does not have. It must not wait for
// them: freeing the grids it read ran a parallel_for there that waited for ever (`lighthouse
// import` hung in CI). With the parent's pool busy all along, every trial read must finish
// (a child that waits shows up as NotIsolated at the 20 s deadline).
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
    for (int i = 0; i < 20; ++i) read += probeVdbReadable(exampleFile(), 0, 20.0) == ProbeResult::Read;
    stop = true;
    busy.join();
    EXPECT_EQ(read, 20);
}

}  // namespace
}  // namespace lh
