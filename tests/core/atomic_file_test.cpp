#include "core/atomic_file.h"
#include "core/errors.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>

namespace lh {
namespace {

namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
    fs::path dir = fs::temp_directory_path() / ("lh_atomic_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

TEST(AtomicOutput, CommitRenamesOntoFinalPath) {
    fs::path dir = freshDir("commit");
    const std::string target = (dir / "out.txt").string();
    {
        AtomicOutput out(target);
        std::ofstream(out.tempPath()) << "hello";
        EXPECT_FALSE(fs::exists(target));  // nothing under the final name until commit
        out.commit();
    }
    EXPECT_TRUE(fs::exists(target));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(AtomicOutput, AbandonedWriteLeavesNothing) {
    fs::path dir = freshDir("abandon");
    {
        AtomicOutput out((dir / "out.txt").string());
        std::ofstream(out.tempPath()) << "half";
    }
    EXPECT_TRUE(fs::is_empty(dir));
}

TEST(AtomicOutput, MissingDirectoryIsAFileError) {
    EXPECT_THROW(AtomicOutput("/nonexistent_dir_lh/out.exr"), FileError);
    EXPECT_EQ(fileExtension("a/b.EXR"), ".exr");
    EXPECT_EQ(fileExtension("noext"), "");
}

// A folder the process may not write to: /sys for root (sysfs refuses new files even to
// root), a read-only temporary folder for anyone else.
std::string unwritableFolder() {
    if (::geteuid() == 0) return fs::is_directory("/sys") ? "/sys" : "";
    const fs::path dir = freshDir("read_only");
    fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
    return dir.string();
}

TEST(AtomicOutput, AnUnwritableFolderIsNamedWithTheReason) {
    const std::string folder = unwritableFolder();
    if (folder.empty()) GTEST_SKIP() << "no unwritable folder here";
    const std::string path = folder + "/lh_atomic_probe.png";
    for (int form = 0; form < 2; ++form) {
        try {
            if (form == 0)
                AtomicOutput out(path);
            else
                requireWritableOutput(path);
            FAIL() << "no error for " << path;
        } catch (const FileError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("cannot create a file in the folder '" + folder + "'"),
                      std::string::npos)
                << what;
            EXPECT_TRUE(what.find("Permission denied") != std::string::npos ||
                        what.find("Read-only file system") != std::string::npos)
                << what;
            EXPECT_NE(what.find("write permission is needed"), std::string::npos) << what;
        }
    }
    EXPECT_FALSE(fs::exists(path));
}

TEST(AtomicOutput, AWriterThatWroteNothingIsReported) {
    const std::string path = (freshDir("empty") / "empty.txt").string();
    {
        AtomicOutput out(path);
        EXPECT_TRUE(fs::exists(out.tempPath()));  // created at once, empty
        EXPECT_THROW(out.commit(), FileError);
    }
    EXPECT_FALSE(fs::exists(path));
    requireWritableOutput(path);  // a writable folder: no error, and nothing left behind
    EXPECT_FALSE(fs::exists(path));
    for (const auto& entry : fs::directory_iterator(fs::path(path).parent_path()))
        EXPECT_EQ(entry.path().filename().string().find(".empty.tmp"), std::string::npos)
            << entry.path();
}

TEST(AtomicOutput, NamesNearTheFileNameLimitStillGetATemporary) {
    fs::path dir = freshDir("long");
    const std::string name = std::string(kMaxFileNameBytes - 4, 'n') + ".vdb";  // 255 bytes
    const std::string target = (dir / name).string();
    {
        AtomicOutput out(target);
        EXPECT_LE(fs::path(out.tempPath()).filename().string().size(), kMaxFileNameBytes);
        EXPECT_EQ(fs::path(out.tempPath()).extension(), ".vdb");
        std::ofstream(out.tempPath()) << "data";
        out.commit();
    }
    EXPECT_TRUE(fs::is_regular_file(target));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace lh
