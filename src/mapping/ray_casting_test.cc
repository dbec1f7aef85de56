#include "mapping/ray_casting.h"

#include <gtest/gtest.h>

#include "mapping/testing/synthetic_world.h"

namespace semchain::mapping {
namespace {

std::vector<Eigen::Vector2i> Trace(Eigen::Vector2d a, Eigen::Vector2d b) {
  std::vector<Eigen::Vector2i> cells;
  TraceSegmentCells(a, b, &cells);
  return cells;
}

TEST(TraceSegmentCellsTest, HorizontalRayStepsCellByCell) {
  const auto cells = Trace({0.5, 0.5}, {4.5, 0.5});
  ASSERT_EQ(cells.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(cells[i], Eigen::Vector2i(i, 0));
}

TEST(TraceSegmentCellsTest, NegativeDirectionAndSameCell) {
  const auto cells = Trace({0.5, 0.5}, {-2.5, 0.5});
  ASSERT_EQ(cells.size(), 3u);
  EXPECT_EQ(cells[2], Eigen::Vector2i(-2, 0));
  EXPECT_TRUE(Trace({0.2, 0.2}, {0.8, 0.9}).empty());
}

TEST(TraceSegmentCellsTest, SlopedRayIsFourConnected) {
  const auto cells = Trace({0.5, 0.5}, {3.7, 2.2});
  ASSERT_FALSE(cells.empty());
  EXPECT_EQ(cells.front(), Eigen::Vector2i(0, 0));
  for (std::size_t i = 1; i < cells.size(); ++i) {
    EXPECT_EQ((cells[i] - cells[i - 1]).cwiseAbs().sum(), 1);
  }
  // The next step from the last cell reaches the end cell (3, 2).
  EXPECT_EQ((Eigen::Vector2i(3, 2) - cells.back()).cwiseAbs().sum(), 1);
}

TEST(ScanInserterTest, WallOccupiedSpaceInFrontFree) {
  // A laser at the origin facing a wall at x = 2 m.
  LaserScan scan;
  scan.angle_min = 0.0;
  scan.angle_increment = 0.0;
  scan.max_range = 30.0;
  scan.ranges = {2.0, 2.0, 2.0};
  OccupancyGrid grid;
  InsertScan(PrepareScan(scan, Pose2(), {}), Pose2(0.01, 0.01, 0.0), &grid);
  // Three beams along the same line: the wall cell got exactly one hit, the cells in front
  // exactly one miss (one update per cell and scan).
  EXPECT_NEAR(grid.LogOdds(grid.CellOf({2.01, 0.01})), 0.847, 1e-6);
  EXPECT_EQ(grid.Find(grid.CellOf({2.01, 0.01}))->hits, 1);
  for (double x = 0.02; x < 1.95; x += 0.05) {
    EXPECT_NEAR(grid.LogOdds(grid.CellOf({x, 0.01})), -0.405, 1e-6) << x;
  }
  EXPECT_EQ(grid.Find(grid.CellOf({2.1, 0.01}))->observations, 0);  // behind the wall
}

TEST(ScanInserterTest, NoReturnBeamsLeaveTheMapAlone) {
  LaserScan scan;
  scan.angle_increment = 0.01;
  scan.max_range = 81.9;
  scan.ranges = {81.91, 81.91};
  OccupancyGrid grid;
  InsertScan(PrepareScan(scan, Pose2(), {}), Pose2(), &grid);
  EXPECT_TRUE(grid.KnownBounds().empty());
  ScanPreparationOptions clear;
  clear.no_return_clear_meters = 1.0;
  InsertScan(PrepareScan(scan, Pose2(), clear), Pose2(), &grid);
  EXPECT_LT(grid.LogOdds(grid.CellOf({0.98, 0.0})), 0.0f);
  const GridCell* beyond = grid.Find(grid.CellOf({1.2, 0.0}));
  EXPECT_TRUE(beyond == nullptr || !beyond->Known());
}

TEST(ScanInserterTest, LaserOffsetIsApplied) {
  LaserScan scan;
  scan.max_range = 30.0;
  scan.ranges = {1.0};
  OccupancyGrid grid;
  // Laser 0.5 m ahead of the robot, robot at (1, 1) facing +y: the hit is at (1, 2.5).
  InsertScan(PrepareScan(scan, Pose2(0.5, 0.0, 0.0), {}), Pose2(1.0, 1.0, kPi / 2), &grid);
  EXPECT_GT(grid.LogOdds(grid.CellOf({1.0, 2.52})), 0.0f);
}

TEST(ScanInserterTest, RoomScanMarksItsWalls) {
  const auto world = testing::RoomWorld();
  const Pose2 pose(0.0, 0.0, 0.0);
  OccupancyGrid grid;
  InsertScan(PrepareScan(testing::SimulateScan(world, pose), Pose2(), {}), pose, &grid);
  // A wall on a cell border may land in either neighbour.
  auto occupied_near = [&grid](double x, double y) {
    return std::max(grid.LogOdds(grid.CellOf({x - 0.01, y})),
                    grid.LogOdds(grid.CellOf({x + 0.01, y}))) > 0.0f;
  };
  EXPECT_TRUE(occupied_near(5.0, 0.0));
  EXPECT_TRUE(occupied_near(1.0, 1.2));  // the box's near face
  EXPECT_LT(grid.LogOdds(grid.CellOf({2.5, 0.0})), 0.0f);
}

}  // namespace
}  // namespace semchain::mapping
