#include "semantic/map_folder_writer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "semantic/map_folder.h"

namespace semchain::semantic {
namespace {

namespace fs = std::filesystem;

MapFolderContents Contents(const SemanticMap& semantic, const KeyframeDatabase& keyframes) {
  MapFolderContents contents;
  contents.occupancy.width = 4;
  contents.occupancy.height = 3;
  contents.occupancy.cells = {0, 0, 0, 0, 0, 100, 100, 0, -1, -1, 0, 0};
  contents.trajectory = {{0.0, Pose2(0.1, 0.1, 0.0)}, {0.1, Pose2(0.12, 0.1, 0.01)}};
  contents.semantic = &semantic;
  contents.keyframes = &keyframes;
  return contents;
}

// Files in 'dir' other than the staging and previous folders' leftovers.
int Leftovers(const fs::path& dir) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    count += entry.path().filename().string().rfind(".out.", 0) == 0;
  }
  return count;
}

TEST(MapFolderWriterTest, WritesAFolderTheReaderLoadsAndReplacesAPreviousOne) {
  const fs::path root = fs::path(testing::TempDir()) / "map_folder_writer";
  fs::remove_all(root);
  fs::create_directories(root / "out");
  std::ofstream(root / "out" / "stale.txt") << "from an earlier map\n";
  SemanticMap semantic;
  semantic.classes = {"door"};
  semantic.objects = {{0, "door", {0.1, 0.1}, {}, 3, 0.9}};
  const KeyframeDatabase keyframes{"", {}};
  const Status written = WriteMapFolder(root / "out/", Contents(semantic, keyframes));
  ASSERT_TRUE(written.ok()) << written.message();
  EXPECT_FALSE(fs::exists(root / "out" / "stale.txt"));
  for (const char* name :
       {"map.yaml", "map.pgm", "trajectory.txt", "semantic.json", "keyframes.json"}) {
    EXPECT_TRUE(fs::exists(root / "out" / name)) << name;
  }
  const Result<MapFolder> read = ReadMapFolder(root / "out");
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(read->semantic.objects.size(), 1u);
  EXPECT_EQ(Leftovers(root), 0);
}

TEST(MapFolderWriterTest, AFailingExtraLeavesThePreviousFolderAsItWas) {
  const fs::path root = fs::path(testing::TempDir()) / "map_folder_writer_failing";
  fs::remove_all(root);
  fs::create_directories(root / "out");
  std::ofstream(root / "out" / "map.yaml") << "the old map\n";
  SemanticMap semantic;
  const KeyframeDatabase keyframes{"", {}};
  const Status written = WriteMapFolder(root / "out", Contents(semantic, keyframes),
                                        [](const fs::path&) { return Status::Error("disk full"); });
  EXPECT_FALSE(written.ok());
  std::ifstream old(root / "out" / "map.yaml");
  std::string line;
  std::getline(old, line);
  EXPECT_EQ(line, "the old map");
  EXPECT_EQ(Leftovers(root), 0);
}

TEST(MapFolderWriterTest, AnUnwritablePlaceIsAnErrorNamingIt) {
  SemanticMap semantic;
  const KeyframeDatabase keyframes{"", {}};
  const Status written = WriteMapFolder("/proc/semchain_map", Contents(semantic, keyframes));
  ASSERT_FALSE(written.ok());
  EXPECT_NE(written.message().find("/proc/semchain_map"), std::string::npos) << written.message();
}

}  // namespace
}  // namespace semchain::semantic
