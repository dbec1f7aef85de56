#include "eval/log_localization_trials.h"

#include <gtest/gtest.h>

#include <optional>

#include "core/angles.h"
#include "mapping/testing/synthetic_map.h"

namespace semchain::eval {
namespace {

TEST(Nav2ProtocolTest, SetsThePeersParametersAndKeepsTrialsSeedAndMethod) {
  LogTrialOptions base;
  base.trials = 7;
  base.seed = 42;
  base.method = "scanmatch-global";
  base.amcl.alpha1 = 0.01;
  const LogTrialOptions nav2 = Nav2Protocol(base);
  EXPECT_EQ(nav2.trials, 7);
  EXPECT_EQ(nav2.seed, 42u);
  EXPECT_EQ(nav2.method, "scanmatch-global");
  EXPECT_EQ(nav2.amcl.max_particles, 20000);
  EXPECT_EQ(nav2.amcl.min_particles, 500);
  EXPECT_DOUBLE_EQ(nav2.amcl.pf_err, 0.05);
  EXPECT_DOUBLE_EQ(nav2.amcl.pf_z, 0.99);
  EXPECT_DOUBLE_EQ(nav2.amcl.z_hit, 0.5);
  EXPECT_DOUBLE_EQ(nav2.amcl.z_rand, 0.5);
  EXPECT_DOUBLE_EQ(nav2.amcl.sigma_hit, 0.2);
  EXPECT_EQ(nav2.amcl.max_beams, 60);
  EXPECT_EQ(nav2.amcl.laser_model_type, localization::LaserModelType::kLikelihoodField);
  EXPECT_DOUBLE_EQ(nav2.amcl.alpha1, 0.2);  // the base's alpha is overruled
  EXPECT_DOUBLE_EQ(nav2.amcl.alpha4, 0.2);
  EXPECT_DOUBLE_EQ(nav2.amcl.update_min_d, 0.25);
  EXPECT_DOUBLE_EQ(nav2.amcl.update_min_a, 0.2);
  EXPECT_DOUBLE_EQ(nav2.window_seconds, 60.0);
  EXPECT_EQ(nav2.success_updates, 5);
  EXPECT_DOUBLE_EQ(nav2.success_distance_meters, 0.25);
  EXPECT_DOUBLE_EQ(nav2.success_angle_radians, DegToRad(10.0));
  EXPECT_TRUE(nav2.perturb_odometry);
  EXPECT_EQ(nav2.odometry_noise.seed, 42u);
  EXPECT_DOUBLE_EQ(nav2.odometry_noise.distance_scale_error, 0.0);
  std::string error;
  EXPECT_TRUE(nav2.Validate(&error)) << error;
}

// Two trials on the synthetic room, scored by the nav2 protocol's streak rule.
LogTrialOptions RoomTrialOptions() {
  LogTrialOptions options;
  options.trials = 2;
  options.seed = 3;
  options.window_seconds = 30.0;
  options.amcl.max_particles = 3000;
  options.success_updates = 5;
  return options;
}

// The odometry is expressed in a frame 100 m and 1 rad away from the map's (AMCL only uses its
// increments): scored against it every trial would fail; scored against the truth they
// converge. Under the streak rule a trial ends at the update that completes 5 updates within
// tolerance.
TEST(LogTrialsTest, StreakRuleScoresAgainstTheTruthAndEndsAtConvergence) {
  mapping::testing::SimulatedRun run = mapping::testing::SimulateRoomRun(0.1, 0.01, 2);
  const Pose2 odometry_frame(100.0, -40.0, 1.0);
  for (StampedScan& s : run.scans) {
    s.odometry = odometry_frame * s.odometry;
    s.laser_pose = odometry_frame * s.laser_pose;
  }
  const LogTrialOptions options = RoomTrialOptions();
  const std::vector<LogTrial> trials =
      RunLogTrials(run.scans, mapping::testing::RoomMap(), options, {}, run.truth);
  ASSERT_EQ(trials.size(), 2u);
  for (const LogTrial& t : trials) {
    EXPECT_TRUE(t.success) << "trial " << t.trial;
    EXPECT_TRUE(t.reached);
    EXPECT_EQ(t.updates, t.iterations);  // nothing run after convergence
    EXPECT_GE(t.iterations, 5);
    ASSERT_TRUE(t.time_s.has_value());
    ASSERT_TRUE(t.reach_time_s.has_value());
    EXPECT_GT(*t.time_s, *t.reach_time_s);  // the streak completes after its first update
    ASSERT_TRUE(t.streak_start_time_s.has_value());
    EXPECT_GE(*t.streak_start_time_s, *t.reach_time_s);
    EXPECT_LT(*t.streak_start_time_s, *t.time_s);
    EXPECT_LE(t.error_m, options.success_distance_meters);
  }
  const LogTrialSummary summary = Summarize(trials);
  EXPECT_EQ(summary.successes, 2);
  ASSERT_TRUE(summary.median_time_s.has_value());
  EXPECT_GT(summary.cpu_ms_per_update, 0.0);
}

// --filter-seed: other random streams for the filters on the same trials (start scans), and the
// default stream when it equals the seed.
TEST(LogTrialsTest, FilterSeedChangesTheStreamsNotTheTrials) {
  const mapping::testing::SimulatedRun run = mapping::testing::SimulateRoomRun(0.1, 0.01, 2);
  const LogTrialOptions options = RoomTrialOptions();
  const auto run_trials = [&](std::optional<std::uint64_t> filter_seed) {
    LogTrialOptions o = options;
    o.filter_seed = filter_seed;
    return RunLogTrials(run.scans, mapping::testing::RoomMap(), o, {}, run.truth);
  };
  const std::vector<LogTrial> plain = run_trials(std::nullopt);
  const std::vector<LogTrial> same = run_trials(3);
  const std::vector<LogTrial> other = run_trials(4);
  ASSERT_EQ(plain.size(), 2u);
  ASSERT_EQ(same.size(), 2u);
  ASSERT_EQ(other.size(), 2u);
  bool any_differs = false;
  for (std::size_t i = 0; i < plain.size(); ++i) {
    EXPECT_EQ(plain[i].start_scan, same[i].start_scan);
    EXPECT_EQ(plain[i].start_scan, other[i].start_scan);
    EXPECT_EQ(plain[i].error_m, same[i].error_m);
    EXPECT_EQ(plain[i].iterations, same[i].iterations);
    any_differs = any_differs || plain[i].error_m != other[i].error_m;
  }
  EXPECT_TRUE(any_differs);
}

}  // namespace
}  // namespace semchain::eval
