#include "core/data_path.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace semchain {
namespace {

namespace fs = std::filesystem;

// A scratch folder per test, with prefixes laid out as `cmake --install` lays them out.
class DataPathTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ =
        fs::temp_directory_path() /
        ("semchain_data_path_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path Touch(const fs::path& relative) {
    const fs::path path = root_ / relative;
    fs::create_directories(path.parent_path());
    std::ofstream(path) << "x";
    return path;
  }

  fs::path root_;
};

TEST_F(DataPathTest, FindsTheShareFolderBesideBinAndBelowLibSemchain) {
  Touch("prefix/share/semchain/models/detector.onnx");
  const std::vector<fs::path> from_bin = DataDirectories(root_ / "prefix/bin/semchain", "");
  ASSERT_EQ(from_bin.size(), 1u);
  EXPECT_EQ(from_bin[0], root_ / "prefix/share/semchain");
  const std::vector<fs::path> from_lib =
      DataDirectories(root_ / "prefix/lib/semchain/semchain_ros", "");
  ASSERT_EQ(from_lib.size(), 1u);
  EXPECT_EQ(from_lib[0], root_ / "prefix/share/semchain");
}

TEST_F(DataPathTest, LooksNoHigherThanTwoFoldersAboveTheExecutable) {
  Touch("prefix/share/semchain/models/detector.onnx");
  EXPECT_TRUE(DataDirectories(root_ / "prefix/a/b/c/semchain", "").empty());
}

TEST_F(DataPathTest, TheConfiguredDataFolderComesAfterTheExecutablesOwn) {
  Touch("moved/share/semchain/worlds/w.yaml");
  Touch("configured/share/semchain/worlds/w.yaml");
  const fs::path configured = root_ / "configured/share/semchain";
  const std::vector<fs::path> dirs = DataDirectories(root_ / "moved/bin/semchain", configured);
  ASSERT_EQ(dirs.size(), 2u);
  EXPECT_EQ(dirs[0], root_ / "moved/share/semchain");
  EXPECT_EQ(dirs[1], configured);
  // Installed where it was configured to be: the one folder once.
  EXPECT_EQ(DataDirectories(root_ / "configured/bin/semchain", configured).size(), 1u);
  // A folder that does not exist is left out.
  EXPECT_TRUE(DataDirectories(root_ / "elsewhere/bin/semchain", root_ / "missing").empty());
}

TEST_F(DataPathTest, ARelativePathNotInTheCurrentFolderIsTakenFromTheFirstDataFolderHoldingIt) {
  Touch("first/config/slam.yaml");
  Touch("second/config/slam.yaml");
  Touch("second/models/detector.onnx");
  const std::vector<fs::path> dirs = {root_ / "first", root_ / "second"};
  EXPECT_EQ(ResolveDataPath("config/slam.yaml", dirs), root_ / "first/config/slam.yaml");
  EXPECT_EQ(ResolveDataPath("models/detector.onnx", dirs), root_ / "second/models/detector.onnx");
  // Nowhere: unchanged, for the error message.
  EXPECT_EQ(ResolveDataPath("models/none.onnx", dirs), fs::path("models/none.onnx"));
}

TEST_F(DataPathTest, APathThatExistsAsGivenOrIsAbsoluteIsKept) {
  Touch("data/worlds/w.yaml");
  const std::vector<fs::path> dirs = {root_ / "data"};
  const fs::path absolute = Touch("mine/worlds/w.yaml");
  EXPECT_EQ(ResolveDataPath(absolute, dirs), absolute);
  EXPECT_EQ(ResolveDataPath("/no/such/worlds/w.yaml", dirs), fs::path("/no/such/worlds/w.yaml"));
  // Relative to the current folder first: the user's own copy wins over the shipped one.
  const fs::path before = fs::current_path();
  fs::current_path(root_ / "mine");
  const fs::path resolved = ResolveDataPath("worlds/w.yaml", dirs);
  fs::current_path(before);
  EXPECT_EQ(resolved, fs::path("worlds/w.yaml"));
}

}  // namespace
}  // namespace semchain
