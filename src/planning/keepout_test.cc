#include "planning/keepout.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace semchain::planning {
namespace {

namespace fs = std::filesystem;

fs::path WriteTemp(const std::string& name, const std::string& text) {
  const fs::path path =
      fs::temp_directory_path() / ("semchain_keepout_" + std::to_string(::getpid()) + name);
  std::ofstream(path) << text;
  return path;
}

TEST(KeepoutTest, ReadsPolygons) {
  const fs::path path = WriteTemp("good.yaml",
                                  "# two zones\n"
                                  "keepout:\n"
                                  "  - [[1, 1], [2, 1], [2, 2]]\n"
                                  "  - [[0, 0], [0.5, 0], [0.5, 0.5], [0, 0.5]]\n");
  const Result<std::vector<Polygon>> zones = ReadKeepoutZones(path);
  ASSERT_TRUE(zones.ok()) << zones.status().message();
  ASSERT_EQ(zones->size(), 2u);
  EXPECT_EQ((*zones)[0].size(), 3u);
  EXPECT_EQ((*zones)[1][2], Eigen::Vector2d(0.5, 0.5));
  fs::remove(path);
}

TEST(KeepoutTest, ErrorsNameLineAndKey) {
  const fs::path two_points = WriteTemp("short.yaml", "keepout:\n  - [[1, 1], [2, 1]]\n");
  Result<std::vector<Polygon>> zones = ReadKeepoutZones(two_points);
  ASSERT_FALSE(zones.ok());
  EXPECT_NE(zones.status().message().find(":2: keepout[0]"), std::string::npos)
      << zones.status().message();
  const fs::path bad_number = WriteTemp("nan.yaml", "keepout:\n  - [[1, 1], [2, x], [0, 2]]\n");
  zones = ReadKeepoutZones(bad_number);
  ASSERT_FALSE(zones.ok());
  EXPECT_NE(zones.status().message().find("keepout[0][1]"), std::string::npos)
      << zones.status().message();
  const fs::path typo = WriteTemp("typo.yaml", "keep_out:\n  - [[1, 1], [2, 1], [0, 2]]\n");
  EXPECT_FALSE(ReadKeepoutZones(typo).ok());
  EXPECT_FALSE(ReadKeepoutZones(WriteTemp("missing_dir", "") / "none.yaml").ok());
  for (const fs::path& p : {two_points, bad_number, typo}) fs::remove(p);
}

}  // namespace
}  // namespace semchain::planning
