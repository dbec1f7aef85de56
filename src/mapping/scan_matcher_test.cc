#include <gtest/gtest.h>

#include "core/angles.h"
#include "mapping/correlative_scan_matcher.h"
#include "mapping/heading_search.h"
#include "mapping/hill_climbing_matcher.h"
#include "mapping/ray_casting.h"
#include "mapping/testing/synthetic_world.h"

namespace semchain::mapping {
namespace {

// A map of the room built from scans at a few known poses.
OccupancyGrid RoomMap() {
  const auto world = testing::RoomWorld();
  OccupancyGrid grid;
  for (const Pose2& pose : {Pose2(0, 0, 0), Pose2(-2, 1, kPi), Pose2(2, -1, kPi / 2),
                            Pose2(-1, -2, -kPi / 2), Pose2(3, 2, 2.5)}) {
    InsertScan(PrepareScan(testing::SimulateScan(world, pose), Pose2(), {}), pose, &grid);
  }
  return grid;
}

MatchPoints ScanAt(const Pose2& pose) {
  return SelectMatchPoints(
      PrepareScan(testing::SimulateScan(testing::RoomWorld(), pose), Pose2(), {}), 30.0);
}

struct Offset {
  double dx, dy, dtheta;
};

class HillClimbingRecoversOffsets : public ::testing::TestWithParam<Offset> {};

TEST_P(HillClimbingRecoversOffsets, WithinAFewMillimetres) {
  const OccupancyGrid grid = RoomMap();
  const LikelihoodField field(grid, {});
  const Pose2 truth(0.37, -0.21, 0.3);
  const Offset offset = GetParam();
  const Pose2 initial(truth.x + offset.dx, truth.y + offset.dy, truth.theta + offset.dtheta);
  const MatchResult result = HillClimb(field, ScanAt(truth), initial, {});
  EXPECT_NEAR(result.pose.x, truth.x, 0.01);
  EXPECT_NEAR(result.pose.y, truth.y, 0.01);
  EXPECT_NEAR(AngleDifference(result.pose.theta, truth.theta), 0.0, DegToRad(0.3));
  EXPECT_GT(result.evaluation.matched, 300);
}

INSTANTIATE_TEST_SUITE_P(Offsets, HillClimbingRecoversOffsets,
                         ::testing::Values(Offset{0.0, 0.0, 0.0}, Offset{0.06, 0.0, 0.0},
                                           Offset{-0.05, 0.04, 0.0}, Offset{0.0, 0.0, 0.04},
                                           Offset{0.04, -0.05, -0.03}, Offset{-0.08, -0.02, 0.02}));

TEST(CorrelativeSearchTest, RecoversOffsetsBeyondHillClimbing) {
  const OccupancyGrid grid = RoomMap();
  const LikelihoodField field(grid, {});
  const Pose2 truth(0.37, -0.21, 0.3);
  const PreparedScan scan =
      PrepareScan(testing::SimulateScan(testing::RoomWorld(), truth), Pose2(), {});
  CorrelativeSearchOptions options;
  options.linear_window_meters = 0.4;
  options.angular_window_radians = 0.25;
  for (const Offset& o : {Offset{0.25, -0.2, 0.15}, Offset{-0.3, 0.1, -0.2}}) {
    const Pose2 initial(truth.x + o.dx, truth.y + o.dy, truth.theta + o.dtheta);
    const MatchResult result = CorrelativeSearch(field, scan, initial, options);
    EXPECT_NEAR(result.pose.x, truth.x, 0.01);
    EXPECT_NEAR(result.pose.y, truth.y, 0.01);
    EXPECT_NEAR(AngleDifference(result.pose.theta, truth.theta), 0.0, DegToRad(0.3));
  }
}

TEST(HeadingSearchTest, BringsAHeadingErrorOfAFastTurnWithinHillClimbingsReach) {
  // 0.35 rad (20°) off and 3 cm out: the error of wheel odometry on a fast turn. Hill climbing
  // alone stays far from the truth; from the swept heading it lands on it.
  const auto world = testing::ClutteredWorld();
  OccupancyGrid grid;
  for (const Pose2& pose : {Pose2(0, 0, 0), Pose2(0, 0, kPi / 2), Pose2(0, 0, kPi),
                            Pose2(0, 0, -kPi / 2), Pose2(0.4, 0.3, 0.7)}) {
    InsertScan(PrepareScan(testing::SimulateScan(world, pose), Pose2(), {}), pose, &grid);
  }
  const LikelihoodField field(grid, {});
  const Pose2 truth(0.2, -0.1, 0.3);
  const MatchPoints points =
      SelectMatchPoints(PrepareScan(testing::SimulateScan(world, truth), Pose2(), {}), 30.0);
  // The optimum of this map (built from five scans of small posts) is itself a centimetre or two
  // from the truth: the match must land on it.
  const Pose2 optimum = HillClimb(field, points, truth, {}).pose;
  ASSERT_LT((optimum.translation() - truth.translation()).norm(), 0.02);
  for (const double error : {0.35, -0.35}) {
    const Pose2 start(truth.x + 0.03, truth.y - 0.02, truth.theta + error);
    const MatchResult alone = HillClimb(field, points, start, {});
    EXPECT_GT(std::abs(AngleDifference(alone.pose.theta, truth.theta)), DegToRad(5.0));
    const HeadingSearchResult swept = SearchHeading(field, points, start, 0.5, 0.02);
    EXPECT_NEAR(AngleDifference(swept.pose.theta, truth.theta), 0.0, 0.03);
    EXPECT_EQ(swept.evaluations, 1 + 2 * 25);
    const MatchResult result = HillClimb(field, points, swept.pose, {});
    EXPECT_NEAR(result.pose.x, optimum.x, 0.01);
    EXPECT_NEAR(result.pose.y, optimum.y, 0.01);
    EXPECT_NEAR(AngleDifference(result.pose.theta, optimum.theta), 0.0, DegToRad(0.3));
  }
}

TEST(LikelihoodFieldTest, TruthScoresBestAndLikelihoodPeaksThere) {
  const OccupancyGrid grid = RoomMap();
  const LikelihoodField field(grid, {});
  const Pose2 truth(0.37, -0.21, 0.3);
  const MatchPoints points = ScanAt(truth);
  const FieldEvaluation at_truth = field.Evaluate(points, truth);
  const FieldEvaluation shifted =
      field.Evaluate(points, Pose2(truth.x + 0.03, truth.y, truth.theta));
  EXPECT_GT(at_truth.score, shifted.score);
  EXPECT_GT(at_truth.log_likelihood, shifted.log_likelihood);
  // All but a few endpoints that fall exactly on cell borders find their obstacle.
  EXPECT_GT(at_truth.matched, static_cast<int>(0.97 * static_cast<double>(points.size())));
  // Nothing known far away: nothing matches, every point gets the floor.
  const FieldEvaluation lost = field.Evaluate(points, Pose2(100, 100, 0));
  EXPECT_EQ(lost.matched, 0);
  const LikelihoodFieldOptions o;
  EXPECT_NEAR(lost.log_likelihood,
              -0.5 * static_cast<double>(points.size()) *
                  (o.max_distance_meters * o.max_distance_meters) /
                  (o.likelihood_sigma_meters * o.likelihood_sigma_meters),
              1e-6);
}

}  // namespace
}  // namespace semchain::mapping
