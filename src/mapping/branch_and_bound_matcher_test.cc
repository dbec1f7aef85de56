#include "mapping/branch_and_bound_matcher.h"

#include <gtest/gtest.h>

#include "core/angles.h"
#include "mapping/ceres_scan_matcher.h"
#include "mapping/occupied_space_cost.h"
#include "mapping/testing/synthetic_map.h"

namespace semchain::mapping {
namespace {

// Returns of a scan simulated in RoomWorld at 'pose', in the robot frame, every 'step'-th beam.
std::vector<Eigen::Vector2d> ScanPoints(const Pose2& pose, int step = 4) {
  const LaserScan scan = testing::SimulateScan(testing::RoomWorld(), pose, 361, 1.5 * kPi, 12.0);
  std::vector<Eigen::Vector2d> points;
  for (std::size_t i = 0; i < scan.size(); i += static_cast<std::size_t>(step)) {
    if (!scan.IsReturn(i)) continue;
    const double a = scan.BeamAngle(i);
    points.emplace_back(scan.ranges[i] * std::cos(a), scan.ranges[i] * std::sin(a));
  }
  return points;
}

// The branch-and-bound search must return what the exhaustive search of its discretisation does.
void ExpectTheSameOptimum(const BranchAndBoundResult& fast,
                          const BranchAndBoundResult& exhaustive) {
  ASSERT_TRUE(fast.found);
  EXPECT_DOUBLE_EQ(fast.score, exhaustive.score);
  EXPECT_NEAR(fast.pose.x, exhaustive.pose.x, 1e-9);
  EXPECT_NEAR(fast.pose.y, exhaustive.pose.y, 1e-9);
  EXPECT_NEAR(fast.pose.theta, exhaustive.pose.theta, 1e-9);
}

class BranchAndBoundTest : public ::testing::Test {
 protected:
  BranchAndBoundTest() : grid_(MakeMatchGrid(testing::RoomMap())) {}
  // A shallow tree and a coarse angular step: small enough to compare with exhaustive search.
  static BranchAndBoundOptions SmallSearch() {
    BranchAndBoundOptions options;
    options.branch_and_bound_depth = 4;
    options.angular_step_radians = 0.02;
    return options;
  }
  MatchGrid grid_;
};

TEST_F(BranchAndBoundTest, FindsTheExhaustiveOptimumOfTheSameDiscretisation) {
  const BranchAndBoundMatcher matcher(grid_, SmallSearch());
  const std::vector<Eigen::Vector2d> points = ScanPoints(Pose2(-1.13, 0.42, 0.31));
  for (const Pose2& center : {Pose2(-1.0, 0.6, 0.4), Pose2(-1.4, 0.2, 0.2)}) {
    SearchWindow window{center, 0.6, 0.2};
    const BranchAndBoundResult exhaustive = matcher.MatchExhaustive(points, window);
    const BranchAndBoundResult fast = matcher.Match(points, window, 0.0);
    ExpectTheSameOptimum(fast, exhaustive);
    // The truth is within a cell and an angular step of the optimum, and the bound pruned.
    EXPECT_NEAR(fast.pose.x, -1.13, 0.06);
    EXPECT_NEAR(fast.pose.y, 0.42, 0.06);
    EXPECT_NEAR(fast.pose.theta, 0.31, 0.021);
    EXPECT_LT(fast.nodes_scored, exhaustive.nodes_scored / 4);
  }
}

// RoomMap with its first 'columns' columns of cells never observed.
MapImage RoomMapWithUnknownWest(int columns) {
  MapImage map = testing::RoomMap();
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < columns; ++x) map.cells[static_cast<std::size_t>(y * map.width + x)] = -1;
  }
  return map;
}

// With unknown_value u, cells the map never observed (and everything outside it) score u,
// observed free cells 0 and returns on walls 1: a map whose west half is unknown.
TEST(MatchGridTest, UnknownCellsAndTheOutsideScoreTheUnknownValue) {
  const MapImage map = RoomMapWithUnknownWest(testing::RoomMap().width / 2);
  MatchGridOptions options;
  options.unknown_value = 0.6;
  const MatchGrid grid = MakeMatchGrid(map, options);
  const MatchGrid plain = MakeMatchGrid(map);
  int unknown_far = 0, free_far = 0;
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      const float m = grid.At(x, y);
      const float m0 = plain.At(x, y);
      if (map.At(x, y) < 0) {
        EXPECT_FLOAT_EQ(m, std::max(m0, 0.6f)) << x << ", " << y;
        unknown_far += m0 == 0.0f;
      } else {
        EXPECT_FLOAT_EQ(m, m0) << x << ", " << y;
        free_far += map.At(x, y) == 0 && m0 == 0.0f;
      }
    }
  }
  EXPECT_GT(unknown_far, 1000);
  EXPECT_GT(free_far, 1000);
  EXPECT_FLOAT_EQ(grid.At(-3, 5), 0.6f);
  EXPECT_FLOAT_EQ(grid.At(map.width + 10, 5), 0.6f);
  EXPECT_FLOAT_EQ(plain.At(-3, 5), 0.0f);
}

// The precomputation grids must still bound every score when unknown cells and the outside
// count u: the search equals the exhaustive one, here with part of the scan off the map.
TEST(MatchGridTest, BranchAndBoundWithUnknownCellsFindsTheExhaustiveOptimum) {
  MatchGridOptions grid_options;
  grid_options.unknown_value = 0.65;
  const MatchGrid grid =
      MakeMatchGrid(RoomMapWithUnknownWest(testing::RoomMap().width / 3), grid_options);
  BranchAndBoundOptions options;
  options.branch_and_bound_depth = 4;
  options.angular_step_radians = 0.02;
  const BranchAndBoundMatcher matcher(grid, options);
  // From near the west wall: some returns land beyond the map's edge.
  std::vector<Eigen::Vector2d> points = ScanPoints(Pose2(-4.6, 0.3, 2.9));
  points.emplace_back(14.0, 0.0);  // beyond the map whatever the pose
  const SearchWindow window{Pose2(-4.4, 0.5, 2.8), 0.6, 0.2};
  const BranchAndBoundResult exhaustive = matcher.MatchExhaustive(points, window);
  const BranchAndBoundResult fast = matcher.Match(points, window, 0.0);
  ExpectTheSameOptimum(fast, exhaustive);
  EXPECT_GT(fast.score, 0.65);
}

TEST_F(BranchAndBoundTest, SkipsTheHeadingsSearchedBefore) {
  const BranchAndBoundMatcher matcher(grid_, SmallSearch());
  const std::vector<Eigen::Vector2d> points = ScanPoints(Pose2(-1.13, 0.42, 0.31));
  // Headings 0.31 ± 0.19 in steps of 0.02: 21; those within ±0.05 (7: up to 3 steps) were
  // searched.
  SearchWindow ring{Pose2(-1.1, 0.4, 0.31), 0.3, 0.19};
  const BranchAndBoundResult all = matcher.Match(points, ring, 0.0);
  ring.searched_angular_window_radians = 0.05;
  const BranchAndBoundResult outer = matcher.Match(points, ring, 0.0);
  EXPECT_EQ(all.angles, 21);
  EXPECT_EQ(outer.angles, 14);
  // The optimum lies in the skipped headings: the ring's best is worse and more than 0.06 off.
  ASSERT_TRUE(outer.found);
  EXPECT_LT(outer.score, all.score);
  EXPECT_GT(std::abs(AngleDifference(outer.pose.theta, 0.31)), 0.06);
  // Centred 0.1 rad away, the optimum is in the ring: found as without skipping.
  SearchWindow shifted{Pose2(-1.1, 0.4, 0.41), 0.3, 0.19};
  const BranchAndBoundResult shifted_all = matcher.Match(points, shifted, 0.0);
  shifted.searched_angular_window_radians = 0.05;
  const BranchAndBoundResult shifted_outer = matcher.Match(points, shifted, 0.0);
  EXPECT_DOUBLE_EQ(shifted_outer.score, shifted_all.score);
  EXPECT_NEAR(shifted_outer.pose.theta, shifted_all.pose.theta, 1e-9);
}

TEST_F(BranchAndBoundTest, MinimumScoreRejectsAWrongScan) {
  const BranchAndBoundMatcher matcher(grid_);
  std::vector<Eigen::Vector2d> points;  // a circle of returns that fits nowhere in the room
  for (int i = 0; i < 90; ++i) {
    points.emplace_back(0.7 * std::cos(i * kPi / 45), 0.7 * std::sin(i * kPi / 45));
  }
  EXPECT_FALSE(matcher.Match(points, {Pose2(0, 0, 0), 1.0, 0.3}, 0.9).found);
}

TEST_F(BranchAndBoundTest, FullMapSearchFindsThePoseWithoutAPrior) {
  BranchAndBoundOptions options;
  options.branch_and_bound_depth = 6;
  const BranchAndBoundMatcher matcher(grid_, options);
  const Pose2 truth(2.2, -1.3, -2.5);
  const BranchAndBoundResult result = matcher.MatchFullMap(ScanPoints(truth, 3), 0.5);
  ASSERT_TRUE(result.found);
  EXPECT_NEAR(result.pose.x, truth.x, 0.06);
  EXPECT_NEAR(result.pose.y, truth.y, 0.06);
  EXPECT_NEAR(AngleDifference(result.pose.theta, truth.theta), 0.0, 0.02);
  EXPECT_GT(result.score, 0.7);
}

TEST_F(BranchAndBoundTest, SaysWhenTheBestPoseLiesOnTheWindowEdge) {
  const BranchAndBoundMatcher matcher(grid_, SmallSearch());
  const Pose2 truth(-1.13, 0.42, 0.31);
  const std::vector<Eigen::Vector2d> points = ScanPoints(truth);
  // The truth inside the window: an interior optimum.
  const BranchAndBoundResult inside =
      matcher.Match(points, {Pose2(-1.08, 0.45, 0.29), 0.2, 0.1}, 0.0);
  ASSERT_TRUE(inside.found);
  EXPECT_FALSE(inside.on_linear_edge);
  EXPECT_FALSE(inside.on_angular_edge);
  // The truth 0.4 m beyond the window in x, or 0.05 rad beyond it in heading: the best pose
  // found is on the border nearest to it.
  const BranchAndBoundResult beyond_x =
      matcher.Match(points, {Pose2(-1.73, 0.42, 0.31), 0.2, 0.1}, 0.0);
  ASSERT_TRUE(beyond_x.found);
  EXPECT_TRUE(beyond_x.on_linear_edge);
  EXPECT_FALSE(beyond_x.on_angular_edge);
  // (The window is rounded outwards to whole cells and angular steps.)
  EXPECT_GE(beyond_x.pose.x, -1.73 + 0.2 - 1e-9);
  EXPECT_LT(beyond_x.pose.x, -1.73 + 0.2 + 0.05);
  const BranchAndBoundResult beyond_heading =
      matcher.Match(points, {Pose2(-1.13, 0.42, 0.16), 0.2, 0.1}, 0.0);
  ASSERT_TRUE(beyond_heading.found);
  EXPECT_TRUE(beyond_heading.on_angular_edge);
  EXPECT_FALSE(beyond_heading.on_linear_edge);
  EXPECT_GE(beyond_heading.pose.theta, 0.16 + 0.1 - 1e-9);
  EXPECT_LT(beyond_heading.pose.theta, 0.16 + 0.1 + 0.02 + 1e-9);
}

TEST_F(BranchAndBoundTest, CeresRefinementRecoversASmallOffset) {
  const Pose2 truth(0.37, -2.11, 1.2);
  const std::vector<Eigen::Vector2d> points = ScanPoints(truth, 2);
  const Pose2 start(truth.x + 0.04, truth.y - 0.03, truth.theta + 0.025);
  const CeresMatchResult result = RefineWithCeres(grid_, points, start);
  EXPECT_NEAR(result.pose.x, truth.x, 0.01);
  EXPECT_NEAR(result.pose.y, truth.y, 0.01);
  EXPECT_NEAR(AngleDifference(result.pose.theta, truth.theta), 0.0, 0.004);
  EXPECT_LT(result.final_cost, result.initial_cost);
  EXPECT_GT(MatchScore(grid_, points, result.pose), MatchScore(grid_, points, start));
}

TEST_F(BranchAndBoundTest, OccupiedSpaceJacobianMatchesCentralDifferences) {
  const Pose2 truth(0.37, -2.11, 1.2);
  const std::vector<Eigen::Vector2d> points = ScanPoints(truth, 8);
  const OccupiedSpaceCost cost(grid_, points, 1.0);
  const std::size_t n = points.size();
  const auto evaluate = [&](const Eigen::Vector3d& pose, double* jacobian) {
    std::vector<double> residuals(n);
    EXPECT_TRUE(cost(pose.data(), residuals.data(), jacobian));
    return Eigen::Map<Eigen::VectorXd>(residuals.data(), static_cast<Eigen::Index>(n)).eval();
  };
  // Off the walls, where M is steep in every direction.
  const Eigen::Vector3d pose(truth.x + 0.023, truth.y - 0.017, truth.theta + 0.02);
  Eigen::Matrix<double, Eigen::Dynamic, 3> analytic(n, 3);  // column-major, as TinySolver's
  const Eigen::VectorXd residuals = evaluate(pose, analytic.data());
  EXPECT_TRUE(residuals.isApprox(evaluate(pose, nullptr)));
  constexpr double kStep = 1e-6;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d step = kStep * Eigen::Vector3d::Unit(k);
    const Eigen::VectorXd numeric =
        (evaluate(pose + step, nullptr) - evaluate(pose - step, nullptr)) / (2.0 * kStep);
    EXPECT_GT(numeric.cwiseAbs().maxCoeff(), 0.1) << "parameter " << k;
    EXPECT_LT((analytic.col(k) - numeric).cwiseAbs().maxCoeff(),
              1e-5 * numeric.cwiseAbs().maxCoeff())
        << "parameter " << k;
  }
}

TEST_F(BranchAndBoundTest, CeresStopsOnASmallStepCloseToTheFullSolve) {
  const Pose2 truth(0.37, -2.11, 1.2);
  const std::vector<Eigen::Vector2d> points = ScanPoints(truth, 2);
  const Pose2 start(truth.x + 0.04, truth.y - 0.03, truth.theta + 0.025);
  CeresScanMatcherOptions full;
  full.step_tolerance = 1e-8;
  const CeresMatchResult solved = RefineWithCeres(grid_, points, start, full);
  const CeresMatchResult stopped = RefineWithCeres(grid_, points, start, {});
  EXPECT_TRUE(stopped.converged);
  EXPECT_LT(stopped.iterations, solved.iterations);
  // The step not taken was below 0.03 × (‖correction‖ + 0.03), ~2.4 mm for this 5 cm one,
  // and the steps shrink: the pose is within a few of them of the full solve.
  EXPECT_LT((stopped.pose.translation() - solved.pose.translation()).norm(), 5e-3);
  EXPECT_LT(std::abs(AngleDifference(stopped.pose.theta, solved.pose.theta)), 5e-3);
  EXPECT_LT(stopped.final_cost, stopped.initial_cost);
}

TEST_F(BranchAndBoundTest, CellScoreIsTheBranchAndBoundScore) {
  const BranchAndBoundMatcher matcher(grid_, {});
  const Pose2 truth(-0.62, 1.35, -2.4);
  const std::vector<Eigen::Vector2d> points = ScanPoints(truth);
  const BranchAndBoundResult match = matcher.Match(points, {Pose2(-0.5, 1.3, -2.3), 0.3, 0.2}, 0.0);
  ASSERT_TRUE(match.found);
  // The search scores M quantized to 1/255 per point.
  EXPECT_NEAR(CellScore(grid_, points, match.pose), match.score, 1.0 / 255.0);
  EXPECT_GT(CellScore(grid_, points, truth), 0.9);
  EXPECT_LT(CellScore(grid_, points, Pose2(truth.x + 0.5, truth.y, truth.theta + 0.3)), 0.5);
  EXPECT_EQ(CellScore(grid_, {}, truth), 0.0);
}

// With a bar, a pose reaching it scores exactly as without one; one that cannot is dropped (-1).
TEST_F(BranchAndBoundTest, CellScoreIfAtLeastKeepsWhatReachesTheBar) {
  const Pose2 truth(-0.62, 1.35, -2.4);
  const std::vector<Eigen::Vector2d> points = ScanPoints(truth);
  const Pose2 off(truth.x + 0.5, truth.y, truth.theta + 0.3);
  const double at_truth = CellScore(grid_, points, truth);
  const double at_off = CellScore(grid_, points, off);
  ASSERT_GT(at_truth, at_off);
  EXPECT_EQ(CellScoreIfAtLeast(grid_, points, truth, at_truth), at_truth);
  EXPECT_EQ(CellScoreIfAtLeast(grid_, points, off, at_off), at_off);
  EXPECT_EQ(CellScoreIfAtLeast(grid_, points, off, at_off + 0.01), -1.0);
  EXPECT_EQ(CellScoreIfAtLeast(grid_, points, off, at_truth), -1.0);
}

}  // namespace
}  // namespace semchain::mapping
