#include "mapping/grid_fusion.h"

#include <gtest/gtest.h>

#include "mapping/map_io.h"

namespace semchain::mapping {
namespace {

GridCell CellWithProbability(double p) {
  GridCell cell;
  cell.log_odds = static_cast<float>(ProbabilityToLogOdds(p));
  cell.observations = 5;
  cell.hits = p > 0.5 ? 5 : 0;
  return cell;
}

bool IsKnown(const OccupancyGrid& grid, int x, int y) {
  const GridCell* cell = grid.Find({x, y});
  return cell != nullptr && cell->Known();
}

double ProbabilityAt(const OccupancyGrid& grid, int x, int y) {
  return LogOddsToProbability(grid.LogOdds({x, y}));
}

// Eq. 10 by hand: 0.7 and 0.6 give 0.42 / (0.42 + 0.12) = 0.7778.
TEST(GridFusionTest, EquationTenOnProbabilities) {
  EXPECT_NEAR(FuseProbabilities(0.7, 0.6), 0.42 / 0.54, 1e-12);
  EXPECT_NEAR(FuseProbabilities(0.5, 0.8), 0.8, 1e-12);  // no evidence changes nothing
  EXPECT_NEAR(FuseProbabilities(0.3, 0.3), 0.09 / (0.09 + 0.49), 1e-12);
  // Clamping: 0.999 counts as 0.98, 0.001 as 0.15.
  EXPECT_NEAR(FuseProbabilities(0.999, 0.001), FuseProbabilities(0.98, 0.15), 1e-12);
  const GridFusionOptions unclamped{1e-9, 1.0 - 1e-9};
  EXPECT_NEAR(FuseProbabilities(0.9, 0.1, unclamped), 0.5, 1e-9);  // symmetric conflict
}

// Hand-made cells in two grids: both free, both occupied, conflicting both ways, and a cell
// known to one grid only (the other unknown), in each direction.
TEST(GridFusionTest, FusesCellByCell) {
  OccupancyGrid lidar;
  OccupancyGrid depth;
  lidar.SetCell({0, 0}, CellWithProbability(0.1));  // both free
  depth.SetCell({0, 0}, CellWithProbability(0.2));
  lidar.SetCell({1, 0}, CellWithProbability(0.9));  // both occupied
  depth.SetCell({1, 0}, CellWithProbability(0.8));
  lidar.SetCell({2, 0}, CellWithProbability(0.01));  // low obstacle: free at the lidar plane
  depth.SetCell({2, 0}, CellWithProbability(0.99));  // occupied in the depth band
  lidar.SetCell({3, 0}, CellWithProbability(0.99));  // occupied for the lidar only
  depth.SetCell({3, 0}, CellWithProbability(0.01));
  lidar.SetCell({4, 0}, CellWithProbability(0.9));  // depth unknown
  depth.SetCell({5, 0}, CellWithProbability(0.3));  // lidar unknown
  const OccupancyGrid fused = FuseGrids(lidar, depth);

  EXPECT_NEAR(ProbabilityAt(fused, 0, 0), FuseProbabilities(0.15, 0.2), 1e-5);
  EXPECT_LT(ProbabilityAt(fused, 0, 0), 0.05);
  EXPECT_NEAR(ProbabilityAt(fused, 1, 0), FuseProbabilities(0.9, 0.8), 1e-5);
  EXPECT_GT(ProbabilityAt(fused, 1, 0), 0.97);
  // Conflicts: a confident obstacle in either grid stays an obstacle (0.98 vs 0.15 → 0.897).
  EXPECT_NEAR(ProbabilityAt(fused, 2, 0), 0.98 * 0.15 / (0.98 * 0.15 + 0.02 * 0.85), 1e-5);
  EXPECT_NEAR(ProbabilityAt(fused, 3, 0), ProbabilityAt(fused, 2, 0), 1e-6);
  // One grid unknown: the other one's (clamped) value.
  EXPECT_NEAR(ProbabilityAt(fused, 4, 0), 0.9, 1e-5);
  EXPECT_NEAR(ProbabilityAt(fused, 5, 0), 0.3, 1e-5);
  // Cells unknown to both stay unknown; observations add up.
  EXPECT_FALSE(IsKnown(fused, 6, 0));
  EXPECT_EQ(fused.Find({0, 0})->observations, 10);
  EXPECT_EQ(fused.Find({5, 0})->observations, 5);

  // As a map_server map: free, occupied, occupied, occupied, occupied, unknown (0.3 lies
  // between the thresholds).
  const MapImage map = GridToMapImage(fused, 0);
  ASSERT_EQ(map.width, 6);
  const std::int8_t expected[6] = {0, 100, 100, 100, 100, -1};
  for (int x = 0; x < 6; ++x) EXPECT_EQ(map.At(x, 0), expected[x]) << x;
}

// Grids whose origins differ by whole cells are aligned by position, not by index.
TEST(GridFusionTest, AlignsGridsByPosition) {
  OccupancyGridOptions options;
  OccupancyGrid a(options, Eigen::Vector2d(0.0, 0.0));
  OccupancyGrid b(options, Eigen::Vector2d(-1.0, 0.0));  // b's cell (20, 0) is a's (0, 0)
  a.SetCell({0, 0}, CellWithProbability(0.9));
  b.SetCell({20, 0}, CellWithProbability(0.9));
  b.SetCell({25, 0}, CellWithProbability(0.9));
  const OccupancyGrid fused = FuseGrids(a, b);
  EXPECT_NEAR(ProbabilityAt(fused, 0, 0), FuseProbabilities(0.9, 0.9), 1e-5);
  EXPECT_NEAR(ProbabilityAt(fused, 5, 0), 0.9, 1e-5);
  EXPECT_FALSE(IsKnown(fused, 1, 0));
}

TEST(GridFusionTest, OptionsValidate) {
  std::string error;
  EXPECT_TRUE(GridFusionOptions{}.Validate(&error));
  EXPECT_FALSE((GridFusionOptions{0.6, 0.9}.Validate(&error)));
}

}  // namespace
}  // namespace semchain::mapping
