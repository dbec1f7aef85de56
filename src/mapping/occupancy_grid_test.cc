#include "mapping/occupancy_grid.h"

#include <gtest/gtest.h>

namespace semchain::mapping {
namespace {

TEST(OccupancyGridTest, CellOfFloorsRelativeToOrigin) {
  const OccupancyGrid grid({}, Eigen::Vector2d(1.0, -2.0));
  EXPECT_EQ(grid.CellOf({1.0, -2.0}), Eigen::Vector2i(0, 0));
  EXPECT_EQ(grid.CellOf({1.049, -1.951}), Eigen::Vector2i(0, 0));
  EXPECT_EQ(grid.CellOf({0.99, -2.01}), Eigen::Vector2i(-1, -1));
  EXPECT_EQ(grid.CellOf({2.0, 0.0}), Eigen::Vector2i(20, 40));
  EXPECT_TRUE(grid.CellCenter({-1, 0}).isApprox(Eigen::Vector2d(0.975, -1.975)));
}

TEST(OccupancyGridTest, UnknownUntilWritten) {
  OccupancyGrid grid;
  EXPECT_EQ(grid.Find({3, 4}), nullptr);
  EXPECT_TRUE(grid.KnownBounds().empty());
  grid.AddMiss({-40, 7});
  ASSERT_NE(grid.Find({-40, 7}), nullptr);
  EXPECT_TRUE(grid.Find({-40, 7})->Known());
  EXPECT_FALSE(grid.Find({-39, 7})->Known());  // same patch, never observed
  const CellBox box = grid.KnownBounds();
  EXPECT_EQ(box.min, Eigen::Vector2i(-40, 7));
  EXPECT_EQ(box.max, Eigen::Vector2i(-40, 7));
}

TEST(OccupancyGridTest, LogOddsAccumulateAndClamp) {
  OccupancyGridOptions options;
  options.max_abs_log_odds = 2.0;
  OccupancyGrid grid(options);
  grid.AddHit({0, 0}, grid.CellCenter({0, 0}));
  EXPECT_NEAR(grid.LogOdds({0, 0}), 0.847, 1e-6);
  grid.AddMiss({0, 0});
  EXPECT_NEAR(grid.LogOdds({0, 0}), 0.847 - 0.405, 1e-6);
  for (int i = 0; i < 10; ++i) grid.AddHit({0, 0}, grid.CellCenter({0, 0}));
  EXPECT_FLOAT_EQ(grid.LogOdds({0, 0}), 2.0f);
  for (int i = 0; i < 20; ++i) grid.AddMiss({0, 0});
  EXPECT_FLOAT_EQ(grid.LogOdds({0, 0}), -2.0f);
}

TEST(OccupancyGridTest, HitsKeepTheMeanEndpoint) {
  OccupancyGrid grid;
  const Eigen::Vector2i cell(2, 3);
  const Eigen::Vector2d center = grid.CellCenter(cell);
  grid.AddHit(cell, center + Eigen::Vector2d(0.01, -0.02));
  grid.AddHit(cell, center + Eigen::Vector2d(0.02, 0.0));
  EXPECT_NEAR(grid.Find(cell)->mean_x, 0.015, 1e-6);
  EXPECT_NEAR(grid.Find(cell)->mean_y, -0.01, 1e-6);
  EXPECT_EQ(grid.Find(cell)->hits, 2);
}

TEST(OccupancyGridTest, CopiesShareUntouchedPatchesAndCloneOnWrite) {
  OccupancyGrid original;
  for (int x = 0; x < 160; ++x) {  // 10 × 10 patches
    for (int y = 0; y < 160; ++y) original.AddMiss({x, y});
  }
  ASSERT_EQ(original.PatchCount(), 100u);
  OccupancyGrid copy = original;
  EXPECT_EQ(UniquePatchBytes({&original, &copy}), 100 * OccupancyGrid::PatchBytes());
  copy.AddHit({5, 5}, copy.CellCenter({5, 5}));
  EXPECT_EQ(UniquePatchBytes({&original, &copy}), 101 * OccupancyGrid::PatchBytes());
  EXPECT_LT(original.LogOdds({5, 5}), 0.0f);  // the original is untouched
  EXPECT_GT(copy.LogOdds({5, 5}), 0.0f);
  copy.AddHit({6, 5}, copy.CellCenter({6, 5}));  // same patch, now owned: no new clone
  EXPECT_EQ(UniquePatchBytes({&original, &copy}), 101 * OccupancyGrid::PatchBytes());
}

TEST(OccupancyGridTest, ManyParticlesSharingAMapUseFarLessThanNTimesIt) {
  OccupancyGrid base;
  for (int x = 0; x < 800; ++x) {  // a 40 m × 40 m map: 2500 patches
    for (int y = 0; y < 800; y += 1) base.AddMiss({x, y});
  }
  const std::size_t map_bytes = UniquePatchBytes({&base});
  std::vector<OccupancyGrid> particles(30, base);
  for (std::size_t i = 0; i < particles.size(); ++i) {  // each changes a 2 m × 2 m area
    for (int x = 0; x < 40; ++x) {
      particles[i].AddHit({400 + x, 400}, particles[i].CellCenter({400 + x, 400}));
    }
  }
  std::vector<const OccupancyGrid*> pointers;
  for (const OccupancyGrid& grid : particles) pointers.push_back(&grid);
  const std::size_t shared_bytes = UniquePatchBytes(pointers);
  EXPECT_LT(shared_bytes, map_bytes + 30 * 4 * OccupancyGrid::PatchBytes());
  EXPECT_LT(shared_bytes * 10, 30 * map_bytes);
}

TEST(OccupancyGridTest, OptionsValidate) {
  std::string error;
  EXPECT_TRUE(OccupancyGridOptions{}.Validate(&error));
  OccupancyGridOptions bad;
  bad.resolution_meters = 0.0;
  EXPECT_FALSE(bad.Validate(&error));
  EXPECT_NE(error.find("resolution"), std::string::npos);
}

}  // namespace
}  // namespace semchain::mapping
