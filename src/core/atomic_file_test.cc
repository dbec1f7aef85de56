#include "core/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace semchain {
namespace {

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("semchain_atomic_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(AtomicFileTest, WritesAndReadsBack) {
  const auto path = dir_ / "a.txt";
  ASSERT_TRUE(WriteFileAtomically(path, "hello\n").ok());
  const Result<std::string> contents = ReadFile(path);
  ASSERT_TRUE(contents.ok());
  EXPECT_EQ(*contents, "hello\n");
}

TEST_F(AtomicFileTest, FailedWriteKeepsTheOldFileAndLeavesNoTemporary) {
  const auto path = dir_ / "map.yaml";
  ASSERT_TRUE(WriteFileAtomically(path, "old").ok());
  const Status status = WriteFileAtomically(path, [](std::ostream& out) {
    out << "half of the new con";
    return Status::Error("generator failed");
  });
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message(), "generator failed");
  EXPECT_EQ(*ReadFile(path), "old");
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir_)) ++files;
  EXPECT_EQ(files, 1);
}

TEST_F(AtomicFileTest, UnwritableLocationIsAnErrorNamingThePath) {
  const auto path = dir_ / "missing_dir" / "x.txt";
  const Status status = WriteFileAtomically(path, "x");
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("missing_dir"), std::string::npos);
  EXPECT_FALSE(ReadFile(path).ok());
}

TEST_F(AtomicFileTest, EnsureWritableDirectoryRejectsAFile) {
  ASSERT_TRUE(WriteFileAtomically(dir_ / "f", "x").ok());
  EXPECT_FALSE(EnsureWritableDirectory(dir_ / "f").ok());
  EXPECT_TRUE(EnsureWritableDirectory(dir_ / "new" / "nested").ok());
}

}  // namespace
}  // namespace semchain
