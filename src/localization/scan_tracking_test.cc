#include "localization/scan_tracking.h"

#include <gtest/gtest.h>

#include "core/angles.h"
#include "mapping/match_grid.h"
#include "mapping/testing/synthetic_map.h"

namespace semchain::localization {
namespace {

class ScanTrackingTest : public ::testing::Test {
 protected:
  ScanTrackingTest() : matcher_(mapping::testing::RoomMap(), ScanMatchRelocalizerOptions()) {}

  std::vector<Eigen::Vector2d> Points(const std::vector<mapping::testing::Segment>& world,
                                      const Pose2& pose) const {
    return matcher_.MatchPoints(mapping::testing::SimulateScan(world, pose, 361, 1.5 * kPi),
                                Pose2());
  }
  static void ExpectNear(const Pose2& a, const Pose2& b, double meters, double radians) {
    EXPECT_LT((a.translation() - b.translation()).norm(), meters) << a << " vs " << b;
    EXPECT_LT(std::abs(AngleDifference(a.theta, b.theta)), radians) << a << " vs " << b;
  }

  const Pose2 truth_{-2.31, 1.17, 2.2};
  ScanMatchRelocalizer matcher_;
};

// A prediction a few centimetres and degrees off: the refinement alone finds the pose.
TEST_F(ScanTrackingTest, RefinesAPredictionNearThePose) {
  const std::vector<Eigen::Vector2d> points = Points(mapping::testing::RoomWorld(), truth_);
  const ScanTrackingResult result =
      TrackScan(matcher_, points, {truth_ * Pose2(0.04, -0.03, 0.03)}, ScanTrackingOptions());
  ASSERT_TRUE(result.matched);
  EXPECT_FALSE(result.searched);
  EXPECT_GT(result.score, 0.9);
  ExpectNear(result.pose, truth_, 0.01, DegToRad(0.3));
}

// Odometry 0.2 m and 15° off (a slip, a late scan): beyond what a refinement may move, the
// window search finds the pose; without a window the scan is not matched.
TEST_F(ScanTrackingTest, SearchesTheWindowWhenThePredictionIsFarOff) {
  const std::vector<Eigen::Vector2d> points = Points(mapping::testing::RoomWorld(), truth_);
  const Pose2 prediction = truth_ * Pose2(0.2, 0.05, DegToRad(15.0));
  const ScanTrackingResult result =
      TrackScan(matcher_, points, {prediction}, ScanTrackingOptions());
  ASSERT_TRUE(result.matched);
  EXPECT_TRUE(result.searched);
  ExpectNear(result.pose, truth_, 0.02, DegToRad(0.6));

  ScanTrackingOptions no_window;
  no_window.search_linear_window_meters = 0.0;
  no_window.search_angular_window_radians = 0.0;
  const ScanTrackingResult refined_only = TrackScan(matcher_, points, {prediction}, no_window);
  EXPECT_FALSE(refined_only.matched);
  EXPECT_FALSE(refined_only.searched);
}

// A place whose scans typically score little (furniture the map does not hold): the right pose
// scores below the relocalizer's own min_score, so the window search takes the tracker's
// threshold; with the relocalizer's it would find nothing and the scan would not be matched.
TEST_F(ScanTrackingTest, SearchesWithItsOwnThresholdWhereScansScoreLittle) {
  // Ten 0.6 m boards 1.5 m around the robot hide most of the walls.
  std::vector<mapping::testing::Segment> furnished = mapping::testing::RoomWorld();
  for (int k = 0; k < 10; ++k) {
    const double a = k * kPi / 5;
    const Eigen::Vector2d c =
        truth_.translation() + 1.5 * Eigen::Vector2d(std::cos(a), std::sin(a));
    const Eigen::Vector2d along = 0.3 * Eigen::Vector2d(-std::sin(a), std::cos(a));
    furnished.push_back({c - along, c + along});
  }
  const std::vector<Eigen::Vector2d> points = Points(furnished, truth_);
  const double truth_score = mapping::CellScore(matcher_.grid(), points, truth_);
  ASSERT_GT(truth_score, 0.3) << truth_score;
  ASSERT_LT(truth_score, ScanMatchRelocalizerOptions().min_score) << truth_score;

  const Pose2 prediction = truth_ * Pose2(0.2, 0.05, DegToRad(15.0));
  mapping::SearchWindow window;
  window.center = prediction;
  window.linear_window_meters = ScanTrackingOptions().search_linear_window_meters;
  window.angular_window_radians = ScanTrackingOptions().search_angular_window_radians;
  EXPECT_FALSE(matcher_.RelocalizeInWindow(points, window).success);

  const ScanTrackingOptions options = ScanTrackingThresholds(ScanTrackingOptions(), truth_score);
  const ScanTrackingResult result = TrackScan(matcher_, points, {prediction}, options);
  ASSERT_TRUE(result.matched);
  EXPECT_TRUE(result.searched);
  ExpectNear(result.pose, truth_, 0.03, DegToRad(1.0));
}

// A scan of another place fits the map nowhere near the prediction where the matches so far
// scored 0.9: not matched, and the caller keeps its own estimate.
TEST_F(ScanTrackingTest, AScanThatDoesNotFitIsNotMatched) {
  const std::vector<Eigen::Vector2d> points =
      Points(mapping::testing::ClutteredWorld(), Pose2(0.0, 0.0, 0.0));
  const ScanTrackingOptions options = ScanTrackingThresholds(ScanTrackingOptions(), 0.9);
  EXPECT_DOUBLE_EQ(options.min_score, 0.45);
  const ScanTrackingResult result = TrackScan(matcher_, points, {Pose2(0.0, 0.0, 0.0)}, options);
  EXPECT_FALSE(result.matched);
  EXPECT_LT(result.score, options.min_score);
  EXPECT_FALSE(TrackScan(matcher_, {}, {truth_}, ScanTrackingOptions()).matched);
}

// A garbled scan whose odometry is right: beyond its first 40 % of beams it holds the room
// turned by 10° (a laser's glitch, FR079's scan 4175 that fit 10.6° off). The turned part fits
// better than the prediction does, and the window search finds it; a searched pose is taken
// only when it scores search_min_ratio of the typical match, so the estimate is not pulled
// degrees off its prediction. Without that bar it is.
TEST_F(ScanTrackingTest, AGarbledScanDoesNotPullTheEstimateOffItsPrediction) {
  LaserScan scan =
      mapping::testing::SimulateScan(mapping::testing::RoomWorld(), truth_, 361, 1.5 * kPi);
  const LaserScan turned = mapping::testing::SimulateScan(
      mapping::testing::RoomWorld(), truth_ * Pose2(0.0, 0.0, DegToRad(10.0)), 361, 1.5 * kPi);
  for (std::size_t i = 145; i < scan.ranges.size(); ++i) scan.ranges[i] = turned.ranges[i];
  const std::vector<Eigen::Vector2d> points = matcher_.MatchPoints(scan, Pose2());
  const double truth_score = mapping::CellScore(matcher_.grid(), points, truth_);
  ASSERT_LT(truth_score, 0.6) << truth_score;  // under the confident score: the window is searched

  ScanTrackingOptions no_bar;
  no_bar.search_min_ratio = 0.0;
  const ScanTrackingResult jumped =
      TrackScan(matcher_, points, {truth_}, ScanTrackingThresholds(no_bar, 0.9));
  ASSERT_TRUE(jumped.matched);
  EXPECT_TRUE(jumped.searched);
  EXPECT_GT(std::abs(AngleDifference(jumped.pose.theta, truth_.theta)), DegToRad(5.0));

  const ScanTrackingOptions options = ScanTrackingThresholds(ScanTrackingOptions(), 0.9);
  EXPECT_DOUBLE_EQ(options.search_min_score, 0.72);
  const ScanTrackingResult held = TrackScan(matcher_, points, {truth_}, options);
  ASSERT_TRUE(held.matched);  // the refinement of the prediction, above min_score
  ExpectNear(held.pose, truth_, 0.03, DegToRad(1.0));

  // A clean scan whose odometry slipped as far is still found by the search under the bar.
  const ScanTrackingResult slipped =
      TrackScan(matcher_, Points(mapping::testing::RoomWorld(), truth_),
                {truth_ * Pose2(0.0, 0.0, DegToRad(-10.0))}, options);
  ASSERT_TRUE(slipped.matched);
  ExpectNear(slipped.pose, truth_, 0.02, DegToRad(0.6));
}

// Boards the map does not hold cover part of the walls, so the right pose scores under the bar
// of searched poses; the odometry slipped 15°, beyond what a refinement may turn, so no
// prediction fits. The search is then the only estimate and needs only min_score.
TEST_F(ScanTrackingTest, WhenNoPredictionFitsASearchedPoseNeedsOnlyTheMinScore) {
  std::vector<mapping::testing::Segment> furnished = mapping::testing::RoomWorld();
  for (int k = 0; k < 8; ++k) {
    const double a = k * kPi / 4 + 0.3;
    const Eigen::Vector2d c =
        truth_.translation() + 1.0 * Eigen::Vector2d(std::cos(a), std::sin(a));
    const Eigen::Vector2d along = 0.3 * Eigen::Vector2d(-std::sin(a), std::cos(a));
    furnished.push_back({c - along, c + along});
  }
  const std::vector<Eigen::Vector2d> points = Points(furnished, truth_);
  const ScanTrackingOptions options = ScanTrackingThresholds(ScanTrackingOptions(), 0.9);
  const double truth_score = mapping::CellScore(matcher_.grid(), points, truth_);
  ASSERT_GT(truth_score, options.min_score) << truth_score;
  ASSERT_LT(truth_score, options.search_min_score) << truth_score;

  const ScanTrackingResult result =
      TrackScan(matcher_, points, {truth_ * Pose2(0.05, 0.0, DegToRad(15.0))}, options);
  ASSERT_TRUE(result.matched);
  EXPECT_TRUE(result.searched);
  ExpectNear(result.pose, truth_, 0.03, DegToRad(1.0));
}

// The thresholds follow the typical score of the matches, within their bounds.
TEST(ScanTrackingOptionsTest, ThresholdsFollowTheTypicalScore) {
  const ScanTrackingOptions options;
  const ScanTrackingOptions sharp = ScanTrackingThresholds(options, 0.9);
  EXPECT_DOUBLE_EQ(sharp.confident_score, 0.75);   // at most confident_score
  EXPECT_DOUBLE_EQ(sharp.min_score, 0.45);         // half the typical score
  EXPECT_DOUBLE_EQ(sharp.search_min_score, 0.72);  // 0.8 of it
  const ScanTrackingOptions cluttered = ScanTrackingThresholds(options, 0.4);
  EXPECT_DOUBLE_EQ(cluttered.confident_score, 0.36);
  EXPECT_DOUBLE_EQ(cluttered.min_score, 0.2);
  const ScanTrackingOptions lost = ScanTrackingThresholds(options, 0.1);
  EXPECT_DOUBLE_EQ(lost.min_score, 0.15);  // the floor, for both
  EXPECT_DOUBLE_EQ(lost.confident_score, 0.15);
  EXPECT_DOUBLE_EQ(lost.search_min_score, 0.15);  // at least min_score
}

TEST(ScanTrackingOptionsTest, Validates) {
  std::string error;
  EXPECT_TRUE(ScanTrackingOptions().Validate(&error)) << error;
  ScanTrackingOptions bad;
  bad.min_score = 1.5;
  EXPECT_FALSE(bad.Validate(&error));
  bad = ScanTrackingOptions();
  bad.max_correction_meters = 0.0;
  EXPECT_FALSE(bad.Validate(&error));
  bad = ScanTrackingOptions();
  bad.search_margin_ratio = 0.9;
  EXPECT_FALSE(bad.Validate(&error));
  bad = ScanTrackingOptions();
  bad.search_min_ratio = 1.5;
  EXPECT_FALSE(bad.Validate(&error));
}

}  // namespace
}  // namespace semchain::localization
