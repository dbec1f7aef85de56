#include "mapping/distance_field.h"

#include <gtest/gtest.h>

#include "mapping/match_grid.h"

namespace semchain::mapping {
namespace {

// A 21 × 21 free map at 0.1 m with one occupied cell in the middle.
MapImage OneObstacle() {
  MapImage map;
  map.width = map.height = 21;
  map.resolution = 0.1;
  map.origin = Eigen::Vector3d(-1.05, -1.05, 0.0);
  map.cells.assign(21 * 21, 0);
  map.cells[10 * 21 + 10] = 100;
  return map;
}

TEST(DistanceFieldTest, EuclideanDistanceToTheNearestOccupiedCellCentre) {
  const DistanceField field(OneObstacle(), 2.0);
  EXPECT_NEAR(field.DistanceAt({0.0, 0.0}), 0.0, 1e-6);
  EXPECT_NEAR(field.DistanceAt({0.3, 0.0}), 0.3, 1e-5);
  EXPECT_NEAR(field.DistanceAt({0.3, 0.4}), 0.5, 1e-5);  // 3-4-5: exact, not a chamfer
  EXPECT_NEAR(field.DistanceAt({-0.6, 0.8}), 1.0, 1e-5);
}

TEST(DistanceFieldTest, CappedAndMaximalOutsideTheMap) {
  const DistanceField field(OneObstacle(), 0.35);
  EXPECT_NEAR(field.DistanceAt({0.3, 0.4}), 0.35, 1e-6);
  EXPECT_NEAR(field.DistanceAt({5.0, 0.0}), 0.35, 1e-6);
  EXPECT_FALSE(field.Contains(field.CellOf({-1.2, 0.0})));
}

TEST(MatchGridTest, GaussianOfTheDistance) {
  MatchGridOptions options;
  options.sigma_meters = 0.1;
  const MatchGrid grid = MakeMatchGrid(OneObstacle(), options);
  EXPECT_NEAR(grid.At(10, 10), 1.0, 1e-6);
  EXPECT_NEAR(grid.At(11, 10), std::exp(-0.5), 1e-6);
  EXPECT_NEAR(grid.At(12, 10), std::exp(-2.0), 1e-6);
  EXPECT_EQ(grid.At(13, 14), 0.0f);  // 0.5 m > 4 σ: cut to 0
  EXPECT_EQ(grid.At(-1, 0), 0.0f);
}

}  // namespace
}  // namespace semchain::mapping
