#include "mapping/map_io.h"

#include <gtest/gtest.h>

#include <fstream>

#include "core/atomic_file.h"
#include "mapping/ray_casting.h"
#include "mapping/testing/synthetic_world.h"

namespace semchain::mapping {
namespace {

class MapIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("semchain_map_io_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  void Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
  }
  std::filesystem::path dir_;
};

MapImage SmallMap() {
  MapImage map;
  map.width = 3;
  map.height = 2;
  map.resolution = 0.05;
  map.origin = Eigen::Vector3d(-1.25, 2.5, 0.0);
  map.cells = {0, 100, -1, 100, 0, 0};  // bottom row first
  return map;
}

TEST_F(MapIoTest, RoundTripIsExact) {
  const MapImage map = SmallMap();
  ASSERT_TRUE(WriteMap(dir_ / "map.yaml", map).ok());
  const Result<MapImage> read = ReadMap(dir_ / "map.yaml");
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(*read, map);
  // Writing what was read gives the same bytes.
  const std::string yaml = *ReadFile(dir_ / "map.yaml");
  const std::string pgm = *ReadFile(dir_ / "map.pgm");
  ASSERT_TRUE(WriteMap(dir_ / "map.yaml", *read).ok());
  EXPECT_EQ(*ReadFile(dir_ / "map.yaml"), yaml);
  EXPECT_EQ(*ReadFile(dir_ / "map.pgm"), pgm);
}

TEST_F(MapIoTest, WritesWhatMapServerExpects) {
  ASSERT_TRUE(WriteMap(dir_ / "map.yaml", SmallMap()).ok());
  EXPECT_EQ(*ReadFile(dir_ / "map.yaml"),
            "image: map.pgm\nmode: trinary\nresolution: 0.05\norigin: [-1.25, 2.5, 0]\n"
            "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const std::string pgm = *ReadFile(dir_ / "map.pgm");
  const std::string pixels = pgm.substr(pgm.size() - 6);
  // Top row first: (100, 0, 0) then (0, 100, -1).
  EXPECT_EQ(pixels, std::string("\x00\xfe\xfe\xfe\x00\xcd", 6));
  EXPECT_EQ(pgm.rfind("P5\n", 0), 0u);
}

TEST_F(MapIoTest, ReadsForeignMaps) {
  // ASCII PGM, negate, and a colour-free 'scale' map with comments.
  Write("m.pgm", "P2\n# hand made\n2 2\n255\n255 0\n128 10\n");
  Write("m.yaml",
        "image: m.pgm\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\nnegate: 1\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.2\nmode: scale\n");
  const Result<MapImage> map = ReadMap(dir_ / "m.yaml");
  ASSERT_TRUE(map.ok()) << map.status().message();
  EXPECT_EQ(map->At(0, 1), 100);  // 255 negated = occupied
  EXPECT_EQ(map->At(1, 1), 0);
  EXPECT_EQ(map->At(1, 0), 0);  // 10 / 255 < 0.2
  EXPECT_GT(map->At(0, 0), 0);  // 128 / 255 = 0.502: scaled
  EXPECT_LT(map->At(0, 0), 100);
}

TEST_F(MapIoTest, ErrorsNameTheProblem) {
  Write("a.yaml", "image: a.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nfree_thresh: 0.2\n");
  Result<MapImage> map = ReadMap(dir_ / "a.yaml");
  ASSERT_FALSE(map.ok());
  EXPECT_NE(map.status().message().find("occupied_thresh"), std::string::npos);
  Write("b.yaml",
        "image: b.pgm\nresolution: 0.05\norigin: [0, 0, 0]\noccupied_thresh: 0.65\n"
        "free_thresh: 0.2\nnegate: 0\n");
  map = ReadMap(dir_ / "b.yaml");
  ASSERT_FALSE(map.ok());
  EXPECT_NE(map.status().message().find("b.pgm"), std::string::npos);
  // Cells the grids cannot take (found by fuzz/map_yaml_fuzzer.cc: 605 m aborted
  // MapImageToGrid) and origins whose cell indices would overflow are errors.
  Write("d.yaml",
        "image: b.pgm\nresolution: 605\norigin: [0, 0, 0]\noccupied_thresh: 0.65\n"
        "free_thresh: 0.2\n");
  map = ReadMap(dir_ / "d.yaml");
  ASSERT_FALSE(map.ok());
  EXPECT_NE(map.status().message().find("d.yaml:1: resolution must be in [0.001, 10] m"),
            std::string::npos)
      << map.status().message();
  Write("e.yaml",
        "image: b.pgm\nresolution: 0.05\norigin: [0, -3e9, 0]\noccupied_thresh: 0.65\n"
        "free_thresh: 0.2\n");
  map = ReadMap(dir_ / "e.yaml");
  ASSERT_FALSE(map.ok());
  EXPECT_NE(map.status().message().find("e.yaml:1: origin: x and y must be within 1000 km"),
            std::string::npos)
      << map.status().message();
  Write("c.pgm", "P5\n4 4\n255\n\x01");
  Write("c.yaml",
        "image: c.pgm\nresolution: 0.05\norigin: [0, 0, 0]\noccupied_thresh: 0.65\n"
        "free_thresh: 0.2\nnegate: 0\n");
  map = ReadMap(dir_ / "c.yaml");
  ASSERT_FALSE(map.ok());
  EXPECT_NE(map.status().message().find("truncated"), std::string::npos);
}

// A header may ask for anything; nothing is allocated for pixels the file does not hold.
TEST_F(MapIoTest, HeadersAskingForHugeImagesAreRefused) {
  const std::string yaml =
      "resolution: 0.05\norigin: [0, 0, 0]\noccupied_thresh: 0.65\nfree_thresh: 0.2\nnegate: 0\n";
  Write("huge.pgm", "P5\n99999 99999\n255\n\x01\x02");
  Write("huge.yaml", "image: huge.pgm\n" + yaml);
  Result<MapImage> map = ReadMap(dir_ / "huge.yaml");
  ASSERT_FALSE(map.ok());
  EXPECT_NE(map.status().message().find("PGM of 99999 x 99999 pixels is larger than the 100 "
                                        "million pixels a map may have"),
            std::string::npos)
      << map.status().message();
  // Within the limit but far more than the file holds: truncated, found before allocating.
  Write("tall.pgm", "P2\n9000 9000\n255\n1 2 3\n");
  Write("tall.yaml", "image: tall.pgm\n" + yaml);
  map = ReadMap(dir_ / "tall.yaml");
  ASSERT_FALSE(map.ok());
  EXPECT_NE(map.status().message().find("truncated (the header asks for 9000 x 9000 pixels)"),
            std::string::npos)
      << map.status().message();
}

// An image that is not a file (a device, a pipe, a folder) is refused instead of read forever;
// an empty one is an error.
TEST_F(MapIoTest, ImagesThatAreNoFilesAreRefused) {
  const std::string yaml =
      "resolution: 0.05\norigin: [0, 0, 0]\noccupied_thresh: 0.65\nfree_thresh: 0.2\n";
  Write("zero.yaml", "image: /dev/zero\n" + yaml);
  Result<MapImage> map = ReadMap(dir_ / "zero.yaml");
  ASSERT_FALSE(map.ok());
  EXPECT_EQ(map.status().message(), "/dev/zero: not a regular file");
  Write("empty.pgm", "");
  Write("empty.yaml", "image: empty.pgm\n" + yaml);
  map = ReadMap(dir_ / "empty.yaml");
  ASSERT_FALSE(map.ok());  // OpenCV threw on it (found by fuzz/map_yaml_fuzzer.cc)
  EXPECT_EQ(map.status().message(), (dir_ / "empty.pgm").string() + ": empty image file");
  std::filesystem::create_directories(dir_ / "folder.pgm");
  Write("folder.yaml", "image: folder.pgm\n" + yaml);
  map = ReadMap(dir_ / "folder.yaml");
  ASSERT_FALSE(map.ok());
  EXPECT_EQ(map.status().message(), (dir_ / "folder.pgm").string() + ": not a regular file");
}

TEST_F(MapIoTest, GridToMapAndBack) {
  OccupancyGrid grid({}, Eigen::Vector2d(0.0, 0.0));
  const Pose2 pose(0.0, 0.0, 0.0);
  const auto world = testing::RoomWorld();
  for (int i = 0; i < 5; ++i) {
    InsertScan(PrepareScan(testing::SimulateScan(world, pose), Pose2(), {}), pose, &grid);
  }
  const MapImage map = GridToMapImage(grid, 2);
  EXPECT_NEAR(map.origin.x(), grid.origin().x() + grid.KnownBounds().min.x() * 0.05 - 0.1, 1e-9);
  int occupied = 0, free = 0;
  for (const std::int8_t c : map.cells) {
    occupied += c == 100;
    free += c == 0;
  }
  EXPECT_GT(occupied, 200);
  EXPECT_GT(free, 5000);
  const OccupancyGrid back = MapImageToGrid(map);
  const Eigen::Vector2i wall = grid.CellOf({2.5, -3.99});
  EXPECT_EQ(back.LogOdds(back.CellOf(grid.CellCenter(wall))) > 0.0f, grid.LogOdds(wall) > 0.6f);
  EXPECT_LT(back.LogOdds(back.CellOf({2.5, 0.0})), 0.0f);
  ASSERT_TRUE(WriteMapPng(dir_ / "map.png", map).ok());
  EXPECT_TRUE(std::filesystem::exists(dir_ / "map.png"));
}

}  // namespace
}  // namespace semchain::mapping
