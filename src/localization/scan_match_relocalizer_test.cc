#include "localization/scan_match_relocalizer.h"

#include <gtest/gtest.h>

#include "core/angles.h"
#include "mapping/testing/synthetic_map.h"

namespace semchain::localization {
namespace {

class ScanMatchRelocalizerTest : public ::testing::Test {
 protected:
  ScanMatchRelocalizerTest() : relocalizer_(mapping::testing::RoomMap(), Options()) {}
  static ScanMatchRelocalizerOptions Options() {
    ScanMatchRelocalizerOptions options;
    options.branch_and_bound.branch_and_bound_depth = 6;
    return options;
  }
  static LaserScan Scan(const Pose2& pose) {
    return mapping::testing::SimulateScan(mapping::testing::RoomWorld(), pose, 361, 1.5 * kPi);
  }
  // A prior at 'pose' with standard deviations 'position_std' (m) and 'heading_std' (rad).
  static PoseHypothesis Prior(const Pose2& pose, double position_std, double heading_std) {
    PoseHypothesis prior;
    prior.pose = pose;
    prior.covariance = Eigen::Vector3d(position_std * position_std, position_std * position_std,
                                       heading_std * heading_std)
                           .asDiagonal();
    return prior;
  }
  // The search of the wide windows alone (no narrow window first).
  static RelocalizationResult RelocalizeWideOnly(const Pose2& truth, const PoseHypothesis& prior) {
    ScanMatchRelocalizerOptions wide_only = Options();
    wide_only.narrow_linear_window_meters = 0.0;
    const ScanMatchRelocalizer wide_relocalizer(mapping::testing::RoomMap(), wide_only);
    return wide_relocalizer.Relocalize(Scan(truth), Pose2(), {prior});
  }
  static void ExpectPoseNear(const Pose2& a, const Pose2& b, double tolerance) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(AngleDifference(a.theta, b.theta), 0.0, tolerance);
  }
  // Asserts that 'result' found 'truth' (2 cm, 0.01 rad).
  static void ExpectFound(const RelocalizationResult& result, const Pose2& truth) {
    ASSERT_TRUE(result.success);
    EXPECT_NEAR(result.pose.x, truth.x, 0.02);
    EXPECT_NEAR(result.pose.y, truth.y, 0.02);
    EXPECT_NEAR(AngleDifference(result.pose.theta, truth.theta), 0.0, 0.01);
  }
  ScanMatchRelocalizer relocalizer_;
};

TEST_F(ScanMatchRelocalizerTest, PriorWindowThenCeresFindsThePose) {
  const Pose2 truth(-2.31, 1.17, 2.2);
  PoseHypothesis wrong, right;
  wrong.pose = Pose2(3.0, -1.0, 0.0);
  wrong.weight = 3.0;
  right.pose = Pose2(truth.x + 0.3, truth.y - 0.25, truth.theta + 0.15);
  right.covariance = Eigen::Vector3d(0.04, 0.04, 0.01).asDiagonal();
  const RelocalizationResult result = relocalizer_.Relocalize(Scan(truth), Pose2(), {wrong, right});
  ExpectFound(result, truth);
  EXPECT_EQ(result.hypothesis, 1);
  EXPECT_GT(mapping::MatchScore(relocalizer_.grid(), relocalizer_.MatchPoints(Scan(truth), Pose2()),
                                result.pose),
            0.8);
  EXPECT_GT(result.nodes_scored, 0);
  // 0.15 rad off lies outside the narrow window: wider headings had to be searched.
  EXPECT_TRUE(result.widened_angular);
}

TEST_F(ScanMatchRelocalizerTest, OnlyTheDimensionCutOffByTheBorderIsWidened) {
  const Pose2 truth(-2.31, 1.17, 2.2);
  // 0.09 rad off: just beyond the narrow headings, well inside its translations.
  const RelocalizationResult turned = relocalizer_.Relocalize(
      Scan(truth), Pose2(),
      {Prior(Pose2(truth.x + 0.05, truth.y - 0.04, truth.theta + 0.09), 0.2, 0.1)});
  ExpectFound(turned, truth);
  EXPECT_TRUE(turned.widened_angular);
  EXPECT_FALSE(turned.widened_linear);
  // 0.6 m off in translation with the right heading: the translations are widened.
  const RelocalizationResult shifted = relocalizer_.Relocalize(
      Scan(truth), Pose2(), {Prior(Pose2(truth.x + 0.6, truth.y, truth.theta), 0.3, 0.1)});
  ExpectFound(shifted, truth);
  EXPECT_TRUE(shifted.widened_linear);
}

TEST_F(ScanMatchRelocalizerTest, WiderHeadingsSkipTheHeadingsSearchedAlready) {
  const Pose2 truth(-2.31, 1.17, 2.2);
  // 0.09 rad off: beyond the narrow headings (0.07), inside twice them; the wide window is 0.3.
  const PoseHypothesis prior =
      Prior(Pose2(truth.x + 0.05, truth.y - 0.04, truth.theta + 0.09), 0.2, 0.1);
  const RelocalizationResult widened = relocalizer_.Relocalize(Scan(truth), Pose2(), {prior});
  const RelocalizationResult wide = RelocalizeWideOnly(truth, prior);
  ExpectFound(widened, truth);
  ASSERT_TRUE(wide.success);
  EXPECT_TRUE(widened.widened_angular);
  EXPECT_FALSE(widened.widened_linear);
  ExpectPoseNear(widened.coarse_pose, wide.coarse_pose, 1e-9);
  // The narrow headings and then only the ring out to twice them: each heading searched once,
  // fewer than the wide window's.
  const mapping::BranchAndBoundMatcher matcher(relocalizer_.grid(), Options().branch_and_bound);
  mapping::SearchWindow twice{prior.pose, Options().narrow_linear_window_meters,
                              2.0 * Options().narrow_angular_window_radians};
  const std::vector<Eigen::Vector2d> points = relocalizer_.MatchPoints(Scan(truth), Pose2());
  EXPECT_EQ(widened.angles, matcher.MatchExhaustive(points, twice).angles);
  EXPECT_LT(widened.angles, wide.angles);
}

TEST_F(ScanMatchRelocalizerTest, AClosePriorIsSettledByTheNarrowWindowWithLessWork) {
  const Pose2 truth(-2.31, 1.17, 2.2);
  PoseHypothesis close;
  close.pose = Pose2(truth.x + 0.08, truth.y - 0.06, truth.theta + 0.03);
  close.covariance = Eigen::Vector3d(0.04, 0.04, 0.01).asDiagonal();
  const RelocalizationResult narrow = relocalizer_.Relocalize(Scan(truth), Pose2(), {close});
  const RelocalizationResult wide = RelocalizeWideOnly(truth, close);
  ASSERT_TRUE(narrow.success);
  ASSERT_TRUE(wide.success);
  EXPECT_FALSE(narrow.widened_linear);
  EXPECT_FALSE(narrow.widened_angular);
  // The same optimum, found over far fewer headings and nodes.
  ExpectPoseNear(narrow.pose, wide.pose, 1e-3);
  EXPECT_NEAR(narrow.pose.x, truth.x, 0.02);
  EXPECT_NEAR(narrow.pose.y, truth.y, 0.02);
  EXPECT_LT(narrow.angles * 2, wide.angles);
  EXPECT_LT(narrow.nodes_scored, wide.nodes_scored);
}

TEST_F(ScanMatchRelocalizerTest, GlobalSearchWithoutPrior) {
  const Pose2 truth(1.9, -2.6, -0.7);
  const RelocalizationResult result = relocalizer_.RelocalizeGlobal(Scan(truth), Pose2());
  ExpectFound(result, truth);
  EXPECT_EQ(result.hypothesis, -1);
}

// The room on a map four times its size, everything outside its walls and inside its two boxes
// unknown: the global search restricted to (nearly) free space finds the same pose as the search
// of every translation, scoring fewer nodes.
TEST_F(ScanMatchRelocalizerTest, GlobalSearchInFreeSpaceFindsTheSamePoseWithLessWork) {
  const Eigen::Vector2d shift(0.025, 0.025);
  mapping::MapImage map = mapping::testing::RasterizeWorld(mapping::testing::RoomWorld(),
                                                           Eigen::Vector2d(-10.0, -8.0) - shift,
                                                           Eigen::Vector2d(10.0, 8.0) - shift);
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      const double wx = map.origin.x() + (x + 0.5) * map.resolution;
      const double wy = map.origin.y() + (y + 0.5) * map.resolution;
      const bool outside = std::abs(wx) > 5.05 || std::abs(wy) > 4.05;
      const bool in_box = (wx > 1.05 && wx < 1.55 && wy > 1.05 && wy < 1.45) ||
                          (wx > -2.95 && wx < -2.25 && wy > -2.45 && wy < -2.05);
      if (outside || in_box) map.cells[static_cast<std::size_t>(y * map.width + x)] = -1;
    }
  }
  ScanMatchRelocalizerOptions whole_map = Options();
  whole_map.global_free_space_margin_meters = -1.0;
  const ScanMatchRelocalizer restricted(map, Options());
  const ScanMatchRelocalizer unrestricted(map, whole_map);
  for (const Pose2& truth : {Pose2(1.9, -2.6, -0.7), Pose2(-4.2, 3.1, 2.5)}) {
    const RelocalizationResult a = restricted.RelocalizeGlobal(Scan(truth), Pose2());
    const RelocalizationResult b = unrestricted.RelocalizeGlobal(Scan(truth), Pose2());
    ExpectFound(a, truth);
    ExpectFound(b, truth);
    EXPECT_DOUBLE_EQ(a.coarse_pose.x, b.coarse_pose.x);
    EXPECT_DOUBLE_EQ(a.coarse_pose.y, b.coarse_pose.y);
    EXPECT_DOUBLE_EQ(a.coarse_pose.theta, b.coarse_pose.theta);
    EXPECT_DOUBLE_EQ(a.score, b.score);
    EXPECT_LT(a.nodes_scored, b.nodes_scored);
  }
}

TEST_F(ScanMatchRelocalizerTest, LaserOffsetIsApplied) {
  const Pose2 robot(0.5, 2.0, -1.0);
  const Pose2 offset(0.2, 0.05, 0.1);
  const RelocalizationResult result = relocalizer_.RelocalizeInWindow(
      Scan(robot * offset), offset, {Pose2(0.7, 1.8, -0.9), 0.5, 0.3});
  ExpectFound(result, robot);
}

}  // namespace
}  // namespace semchain::localization
