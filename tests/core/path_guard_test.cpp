// Outputs that are inputs in another spelling are refused; distinct paths pass.
#include "core/path_guard.h"
#include "core/errors.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace lh {
namespace {

namespace fs = std::filesystem;

struct PathGuardTest : ::testing::Test {
    fs::path dir = fs::temp_directory_path() / "lh_path_guard";
    std::string photo;
    void SetUp() override {
        fs::remove_all(dir);
        fs::create_directories(dir / "export");
        photo = (dir / "photo.png").string();
        std::ofstream(photo) << "pixels";
        std::ofstream(dir / "export" / "level_0.vdb") << "grid";
    }
    void TearDown() override { fs::remove_all(dir); }
    void expectRefused(const std::string& output, const std::vector<NamedInput>& inputs) {
        EXPECT_THROW(requireOutputIsNotAnInput(output, "-o", inputs), InputError) << output;
    }
};

TEST_F(PathGuardTest, TheSameFileInAnySpellingIsRefused) {
    expectRefused(photo, {{photo, "--image"}});
    expectRefused((dir / "." / "photo.png").string(), {{photo, "--image"}});
    expectRefused((dir / "export" / ".." / "photo.png").string(), {{photo, "--image"}});
    fs::create_symlink(photo, dir / "link.png");
    expectRefused((dir / "link.png").string(), {{photo, "--image"}});
    fs::create_hard_link(photo, dir / "hard.png");
    expectRefused((dir / "hard.png").string(), {{photo, "--image"}});
    try {
        requireOutputIsNotAnInput((dir / "link.png").string(), "-o", {{photo, "--image"}});
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("--image"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("overwrite"), std::string::npos) << e.what();
    }
}

TEST_F(PathGuardTest, DirectoriesProtectWhatTheyHoldBothWays) {
    // A file inside an input directory (import reading an export).
    expectRefused((dir / "export" / "level_0.vdb").string(),
                  {{(dir / "export").string(), "EXPORT_DIR"}});
    expectRefused((dir / "export" / "new.vdb").string(),
                  {{(dir / "export").string(), "EXPORT_DIR"}});
    // An output directory that holds an input (export replacing its directory).
    expectRefused((dir / "export").string(),
                  {{(dir / "export" / "level_0.vdb").string(), "input"}});
}

TEST_F(PathGuardTest, DistinctOrMissingPathsPass) {
    EXPECT_NO_THROW(
        requireOutputIsNotAnInput((dir / "out.png").string(), "-o", {{photo, "--image"}}));
    EXPECT_NO_THROW(requireOutputIsNotAnInput((dir / "exported2").string(), "-o",
                                              {{(dir / "export").string(), "EXPORT_DIR"}}));
    EXPECT_NO_THROW(requireOutputIsNotAnInput(
        photo, "-o", {{(dir / "missing.png").string(), "--image"}, {"", "--path"}}));
    EXPECT_FALSE(sameFile(photo, (dir / "missing.png").string()));
    EXPECT_TRUE(sameFile(photo, (dir / "." / "photo.png").string()));
}

}  // namespace
}  // namespace lh
