#include "core/atomic_file.h"
#include "core/errors.h"

#include <gtest/gtest.h>

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
