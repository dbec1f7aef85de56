#include "mapping/scan_localizer.h"

#include <gtest/gtest.h>

#include "core/angles.h"
#include "mapping/ray_casting.h"
#include "mapping/testing/synthetic_world.h"

namespace semchain::mapping {
namespace {

// A short run through the cluttered world (posts, no long walls: a scan turned by more than a
// few degrees has no slope back towards its heading), its scans and the map they make at the
// true poses.
struct ClutteredRun {
  std::vector<Pose2> truth;
  std::vector<PreparedScan> scans;
  OccupancyGrid map;
};

ClutteredRun MakeClutteredRun() {
  const auto world = testing::ClutteredWorld();
  ClutteredRun run;
  for (int i = 0; i <= 40; ++i) {
    run.truth.emplace_back(-1.0 + 0.05 * i, 0.4 - 0.02 * i, 0.03 * i);
    run.scans.push_back(PrepareScan(testing::SimulateScan(world, run.truth.back()), Pose2(), {}));
    InsertScan(run.scans.back(), run.truth.back(), &run.map);
  }
  return run;
}

double HeadingError(const Pose2& pose, const Pose2& truth) {
  return std::abs(AngleDifference(pose.theta, truth.theta));
}

// Odometry that slipped in a turn in place between two processed scans (ACES at t = 789 s):
// one scan's interpolated pose is 11° and a few centimetres off. Hill climbing from there stays
// in a local optimum with too few returns on posts to count as matched; beside matched
// neighbours the scan is searched and lands on its true pose. The scans that fit are left where
// they are.
TEST(LocalizeScansTest, AScanWhosePriorSlippedIsSearchedAndFound) {
  const ClutteredRun run = MakeClutteredRun();
  const LikelihoodField field(run.map, {});
  std::vector<Pose2> priors = run.truth;
  const Pose2& truth = run.truth[20];
  priors[20] = Pose2(truth.x + 0.04, truth.y - 0.03, truth.theta + DegToRad(11.0));

  EveryScanOptions without;
  without.search_below_ratio = 0.0;
  std::vector<Pose2> local = priors;
  const EveryScanStatistics alone = LocalizeScans(field, run.scans, &local, without, 1);
  EXPECT_EQ(alone.searched, 0);
  EXPECT_GT(HeadingError(local[20], truth), DegToRad(5.0));

  for (const int threads : {1, 2}) {
    std::vector<Pose2> poses = priors;
    const EveryScanStatistics statistics =
        LocalizeScans(field, run.scans, &poses, EveryScanOptions(), threads);
    EXPECT_EQ(statistics.matched, static_cast<int>(run.scans.size()));
    EXPECT_EQ(statistics.replaced, 1);
    EXPECT_LE(statistics.searched, 3);
    EXPECT_LT(HeadingError(poses[20], truth), DegToRad(0.3));
    EXPECT_LT((poses[20].translation() - truth.translation()).norm(), 0.02);
    for (std::size_t i = 0; i < poses.size(); ++i) {
      if (i == 20) continue;
      EXPECT_EQ(poses[i].x, local[i].x) << i;  // not searched, or the search did not win
      EXPECT_EQ(poses[i].theta, local[i].theta) << i;
      EXPECT_LT((poses[i].translation() - run.truth[i].translation()).norm(), 0.02) << i;
    }
  }
}

// A scan matched, but far below its neighbours, is searched too; the searched pose replaces
// the local match only when it scores search_margin_ratio times as much (a look-alike within the
// window scores about as well as the local match, and there the interpolated pose is kept).
TEST(LocalizeScansTest, AMatchedScanIsReplacedOnlyByASearchThatWinsByTheMargin) {
  const ClutteredRun run = MakeClutteredRun();
  const LikelihoodField field(run.map, {});
  std::vector<Pose2> priors = run.truth;
  priors[20].theta += DegToRad(11.0);
  EveryScanOptions options;
  options.min_matched_points = 0;  // the turned scan counts as matched, with its low score
  for (const double margin : {1.1, 1e6}) {
    options.search_margin_ratio = margin;
    std::vector<Pose2> poses = priors;
    const EveryScanStatistics statistics = LocalizeScans(field, run.scans, &poses, options, 1);
    EXPECT_EQ(statistics.matched, static_cast<int>(run.scans.size()));
    EXPECT_GE(statistics.searched, 1);
    EXPECT_EQ(statistics.replaced, margin < 2.0 ? 1 : 0);
    if (margin < 2.0) {
      EXPECT_LT(HeadingError(poses[20], run.truth[20]), DegToRad(0.3));
    } else {
      EXPECT_GT(HeadingError(poses[20], run.truth[20]), DegToRad(5.0));
    }
  }
}

// A corridor whose one feature, a door recess, the map holds 0.1 m further along than the scan
// sees it (the map drew it on a pass whose along-track position was off). Hill climbing slides
// the scan along the corridor onto the map's recess; with the prior, the interpolated pose keeps
// the along-track position, and the walls still correct the pose across the corridor.
TEST(LocalizeScansTest, ThePriorHoldsTheInterpolatedPoseAlongACorridor) {
  auto corridor = [](double recess_x) {
    return std::vector<testing::Segment>{{{-20.0, -1.0}, {20.0, -1.0}},
                                         {{-20.0, 1.0}, {recess_x, 1.0}},
                                         {{recess_x, 1.0}, {recess_x, 1.3}},
                                         {{recess_x, 1.3}, {recess_x + 0.9, 1.3}},
                                         {{recess_x + 0.9, 1.3}, {recess_x + 0.9, 1.0}},
                                         {{recess_x + 0.9, 1.0}, {20.0, 1.0}}};
  };
  const double kRange = 8.0;  // the corridor's ends are out of range
  OccupancyGrid map;
  for (int i = -4; i <= 4; ++i) {
    const Pose2 pose(0.5 * i, 0.0, 0.0);
    InsertScan(
        PrepareScan(testing::SimulateScan(corridor(3.0), pose, 361, kPi, kRange), Pose2(), {}),
        pose, &map);
  }
  const LikelihoodField field(map, {});
  const Pose2 truth(0.0, 0.0, 0.0);
  const std::vector<PreparedScan> scans = {
      PrepareScan(testing::SimulateScan(corridor(3.1), truth, 361, kPi, kRange), Pose2(), {})};
  const Pose2 prior(0.0, 0.04, 0.01);  // right along the corridor, off across it

  EveryScanOptions options;  // the default prior: 0.05 m, 0.05 rad
  std::vector<Pose2> held = {prior};
  LocalizeScans(field, scans, &held, options, 1);
  options.prior_sigma_meters = 0.0;
  std::vector<Pose2> free = {prior};
  LocalizeScans(field, scans, &free, options, 1);

  EXPECT_LT(free[0].x, -0.02);  // towards the map's recess (measured: 0.03 m)
  EXPECT_LT(std::abs(held[0].x - prior.x), 0.005);
  for (const Pose2& pose : {free[0], held[0]}) {
    EXPECT_NEAR(pose.y, truth.y, 0.01);
    EXPECT_NEAR(AngleDifference(pose.theta, truth.theta), 0.0, DegToRad(0.3));
  }
}

TEST(LocalizeScansTest, BadSearchOptionsAreRejected) {
  std::string error;
  EveryScanOptions options;
  EXPECT_TRUE(options.Validate(&error)) << error;
  options.search_margin_ratio = 0.9;
  EXPECT_FALSE(options.Validate(&error));
  options = EveryScanOptions();
  options.search.linear_step_meters = 0.0;
  EXPECT_FALSE(options.Validate(&error));
  EXPECT_NE(error.find("search"), std::string::npos) << error;
}

}  // namespace
}  // namespace semchain::mapping
