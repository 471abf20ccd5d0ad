// Temporaries say whose they are, and those of a process that no longer runs are removed by
// the next output written beside them, while a live writer's, another machine's and the
// user's own files stay.
#include "core/temporary_files.h"
#include "core/atomic_file.h"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <csignal>
#include <filesystem>
#include <fstream>

namespace lh {
namespace {

namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
    const fs::path dir =
        fs::temp_directory_path() / ("lh_temporaries_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// The pid of a process that has exited (and been reaped): it no longer runs.
long deadPid() {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    int status = 0;
    ::waitpid(child, &status, 0);
    return long(child);
}

// A child killed with SIGKILL and not yet reaped (a zombie), as a killed command is until its
// parent reaps it. The caller reaps it with waitpid.
pid_t killedUnreapedChild() {
    const pid_t child = ::fork();
    if (child == 0)
        for (;;) ::pause();
    ::kill(child, SIGKILL);
    siginfo_t info{};
    ::waitid(P_PID, id_t(child), &info,
             WEXITED | WNOWAIT);  // until it has died, leaving it unreaped
    return child;
}

// A temporary's name as process `pid` of machine `host` would have made it.
std::string temporaryName(const std::string& stem, long pid, const std::string& host,
                          const std::string& ext) {
    return "." + stem + ".tmp" + std::to_string(pid) + "_0_" + host + ext;
}

TEST(TemporaryFiles, NamesSayWhoMadeThemAndStayWithinTheLimit) {
    const std::string name = fs::path(temporaryBeside("out/room.vdb", "tmp")).filename().string();
    EXPECT_EQ(name.rfind(".room.tmp", 0), 0u) << name;
    EXPECT_EQ(fs::path(name).extension(), ".vdb");
    const auto owner = temporaryOwner(name);
    ASSERT_TRUE(owner.has_value()) << name;
    EXPECT_EQ(owner->pid, long(::getpid()));
    EXPECT_EQ(owner->host, thisHostTag());
    EXPECT_EQ(thisHostTag().size(), 8u);
    // A folder keeps its whole name; two calls never share a name.
    const std::string dir =
        fs::path(temporaryBeside("exports/room.blend", "old", false)).filename().string();
    EXPECT_EQ(dir.rfind(".room.blend.old", 0), 0u) << dir;
    EXPECT_TRUE(temporaryOwner(dir).has_value()) << dir;
    EXPECT_NE(temporaryBeside("a.png", "tmp"), temporaryBeside("a.png", "tmp"));
    const std::string longName = std::string(kMaxFileNameBytes - 4, 'n') + ".exr";
    const std::string longTemporary =
        fs::path(temporaryBeside(longName, "tmp")).filename().string();
    EXPECT_LE(longTemporary.size(), kMaxFileNameBytes);
    EXPECT_EQ(fs::path(longTemporary).extension(), ".exr");
    EXPECT_TRUE(temporaryOwner(longTemporary).has_value());
    // Not temporaries: a user's hidden files, names without the owner, a visible file.
    for (const std::string other :
         {".hidden", ".notes.tmp", ".a.tmp12_3.png", "a.tmp12_3_0123abcd.png",
          ".a.tmp12_3_0123ABCD.png", ".a.bak12_3_0123abcd.png"})
        EXPECT_FALSE(temporaryOwner(other).has_value()) << other;
}

TEST(TemporaryFiles, AKilledProcessesTemporariesGoWithTheNextOutput) {
    const fs::path dir = freshDir("sweep");
    const long dead = deadPid();
    const std::string otherHost = thisHostTag() == "0123abcd" ? "fedc3210" : "0123abcd";
    const fs::path abandonedFile = dir / temporaryName("view", dead, thisHostTag(), ".png");
    const fs::path abandonedDir = dir / temporaryName("export", dead, thisHostTag(), "");
    const pid_t zombie = killedUnreapedChild();
    const fs::path zombies = dir / temporaryName("model", long(zombie), thisHostTag(), ".pt");
    const fs::path live = dir / temporaryName("other", long(::getpid()), thisHostTag(), ".png");
    const fs::path remote = dir / temporaryName("remote", dead, otherHost, ".png");
    const fs::path users = dir / ".view.tmp";
    for (const fs::path& f : {abandonedFile, zombies, live, remote, users})
        std::ofstream(f) << "data";
    fs::create_directories(abandonedDir / "inside");
    std::ofstream(abandonedDir / "inside" / "level_0.vdb") << "data";

    {
        AtomicOutput out((dir / "result.txt").string());
        std::ofstream(out.tempPath()) << "result";
        out.commit();
    }
    EXPECT_FALSE(fs::exists(abandonedFile)) << "a dead process's temporary file is removed";
    EXPECT_FALSE(fs::exists(abandonedDir)) << "a dead process's temporary folder is removed";
    EXPECT_FALSE(fs::exists(zombies))
        << "a killed process's temporary is removed before the process is reaped";
    ::waitpid(zombie, nullptr, 0);
    EXPECT_TRUE(fs::exists(live)) << "a live process's temporary stays";
    EXPECT_TRUE(fs::exists(remote))
        << "another machine's temporary stays (its writer may run there)";
    EXPECT_TRUE(fs::exists(users)) << "a file that only looks like a temporary stays";
    EXPECT_TRUE(fs::is_regular_file(dir / "result.txt"));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace lh
