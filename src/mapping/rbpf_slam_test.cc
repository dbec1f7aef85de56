#include "mapping/rbpf_slam.h"

#include <gtest/gtest.h>

#include "core/angles.h"
#include "mapping/incremental_slam.h"
#include "mapping/laser_odometry.h"
#include "mapping/map_io.h"
#include "mapping/resampling.h"
#include "mapping/slam_pipeline.h"
#include "mapping/testing/synthetic_world.h"

namespace semchain::mapping {
namespace {

// The largest error of the relative motion over 'span' scans (the relation metric's idea).
double MaxRelativeError(const std::vector<Pose2>& estimate, const std::vector<Pose2>& truth,
                        std::size_t span) {
  double worst = 0.0;
  for (std::size_t i = 0; i + span < truth.size(); ++i) {
    const Pose2 e =
        truth[i].Between(truth[i + span]).Between(estimate[i].Between(estimate[i + span]));
    worst = std::max(worst, std::hypot(e.x, e.y));
  }
  return worst;
}

double MaxPositionError(const std::vector<Pose2>& estimate, const std::vector<Pose2>& truth) {
  double worst = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    worst = std::max(worst, (estimate[i].translation() - truth[i].translation()).norm());
  }
  return worst;
}

RbpfOptions SmallFilter(int particles) {
  RbpfOptions options;
  options.particles = particles;
  options.threads = 2;
  options.linear_update_meters = 0.3;
  options.angular_update_radians = 0.2;
  options.match_beam_step = 2;
  return options;
}

TEST(LaserOdometryTest, RemovesTheWheelOdometryDrift) {
  const testing::SimulatedRun run = testing::SimulateRoomRun();
  std::vector<PreparedScan> prepared;
  for (const StampedScan& s : run.scans) prepared.push_back(PrepareScan(s.scan, Pose2(), {}));
  std::vector<Pose2> odometry;
  for (const StampedScan& s : run.scans) odometry.push_back(s.odometry);
  EXPECT_GT(MaxPositionError(odometry, run.truth), 0.5);
  const std::vector<Pose2> laser = ComputeLaserOdometry(run.scans, prepared, {}, {}, {});
  EXPECT_LT(MaxPositionError(laser, run.truth), 0.1);
}

TEST(RbpfSlamTest, WeightsStayNormalised) {
  const testing::SimulatedRun run = testing::SimulateRoomRun(0.2);
  for (const bool genetic : {false, true}) {
    RbpfOptions options = SmallFilter(8);
    options.genetic.enabled = genetic;
    options.annealing.enabled = genetic;
    RbpfSlam slam(options);
    for (std::size_t i = 0; i < run.scans.size(); ++i) {
      if (!slam.AddScan(run.scans[i], static_cast<int>(i))) continue;
      std::vector<double> log_weights;
      for (const Particle& p : slam.particles()) log_weights.push_back(p.log_weight);
      const std::vector<double> weights = NormalizeLogWeights(log_weights, options.weight_gain);
      double sum = 0.0;
      for (const double w : weights) {
        ASSERT_TRUE(std::isfinite(w));
        sum += w;
      }
      EXPECT_NEAR(sum, 1.0, 1e-9);
      const double neff = EffectiveSampleSize(weights);
      EXPECT_GE(neff, 1.0 - 1e-9);
      EXPECT_LE(neff, options.particles + 1e-9);
    }
    EXPECT_GT(slam.statistics().processed, 20);
  }
}

TEST(RbpfSlamTest, SameSeedSameResultWhateverTheThreadCount) {
  const testing::SimulatedRun run = testing::SimulateRoomRun();
  std::vector<Pose2> first;
  for (const int threads : {1, 3}) {
    RbpfOptions options = SmallFilter(6);
    options.threads = threads;
    RbpfSlam slam(options);
    for (std::size_t i = 0; i < 60; ++i) slam.AddScan(run.scans[i], static_cast<int>(i));
    std::vector<Pose2> poses;
    for (const Particle& p : slam.particles()) poses.push_back(p.pose);
    if (first.empty()) {
      first = poses;
      continue;
    }
    for (std::size_t i = 0; i < poses.size(); ++i) {
      EXPECT_DOUBLE_EQ(poses[i].x, first[i].x);
      EXPECT_DOUBLE_EQ(poses[i].theta, first[i].theta);
    }
  }
}

TEST(SlamPipelineTest, EveryScanGetsAnAccuratePose) {
  const testing::SimulatedRun run = testing::SimulateRoomRun(0.2);
  SlamOptions options;
  options.rbpf = SmallFilter(8);
  for (const bool laser_odometry : {true, false}) {
    options.laser_odometry.enabled = laser_odometry;
    const SlamResult result = RunSlam(run.scans, options);
    ASSERT_EQ(result.trajectory.size(), run.scans.size());
    std::vector<Pose2> poses;
    for (const StampedPose& p : result.trajectory) poses.push_back(p.pose);
    EXPECT_LT(MaxPositionError(poses, run.truth), 0.1) << laser_odometry;
    EXPECT_LT(MaxRelativeError(poses, run.truth, 5), 0.02) << laser_odometry;
    EXPECT_LT(result.processed.size(), run.scans.size());
    EXPECT_GT(result.every_scan.matched, static_cast<int>(run.scans.size()) - 5);
  }
}

// A pose graph that closes no loop must leave the result as the filter alone gives it: the map
// the scans are localized in is made of the filter's scans at the nodes' poses, not of every
// scan at poses interpolated between them.
TEST(SlamPipelineTest, APoseGraphWithoutClosuresLeavesTheFilterAsItIs) {
  const testing::SimulatedRun run = testing::SimulateRoomRun(0.2);
  SlamOptions options;
  options.rbpf = SmallFilter(6);
  options.pose_graph = false;
  const SlamResult alone = RunSlam(run.scans, options);
  options.pose_graph = true;
  options.loop_closure.min_score = 1.0;  // no match scores that
  const SlamResult graph = RunSlam(run.scans, options);
  EXPECT_EQ(graph.loop_closure.accepted, 0);
  ASSERT_LT(alone.processed.size(), run.scans.size());  // else there is nothing in between
  ASSERT_EQ(graph.trajectory.size(), alone.trajectory.size());
  for (std::size_t i = 0; i < alone.trajectory.size(); ++i) {
    // The graph hands its nodes back through its own arithmetic: equal up to rounding.
    EXPECT_NEAR(graph.trajectory[i].pose.x, alone.trajectory[i].pose.x, 1e-9) << i;
    EXPECT_NEAR(graph.trajectory[i].pose.y, alone.trajectory[i].pose.y, 1e-9) << i;
    EXPECT_NEAR(graph.trajectory[i].pose.theta, alone.trajectory[i].pose.theta, 1e-9) << i;
  }
  EXPECT_EQ(GridToMapImage(graph.map).cells, GridToMapImage(alone.map).cells);
}

// Finishing an IncrementalSlam for good drops its particles before the final map is built
// (memory); what it returns must be what finishing it and keeping it returns.
TEST(SlamPipelineTest, FinishingForGoodGivesWhatFinishingAndKeepingGives) {
  const testing::SimulatedRun run = testing::SimulateRoomRun(0.2);
  for (const int pose_graph : {0, 1, 2}) {  // none, after the filter, online
    SlamOptions options;
    options.rbpf = SmallFilter(6);
    options.pose_graph = pose_graph > 0;
    options.loop_closure.online = pose_graph == 2;
    IncrementalSlam slam(options);
    for (const StampedScan& scan : run.scans) slam.AddScan(scan);
    const SlamResult kept = slam.Finish();
    ASSERT_FALSE(slam.filter().particles().empty());
    const SlamResult last = std::move(slam).Finish();
    EXPECT_TRUE(slam.filter().particles().empty());  // NOLINT(bugprone-use-after-move)
    ASSERT_EQ(last.trajectory.size(), kept.trajectory.size());
    for (std::size_t i = 0; i < kept.trajectory.size(); ++i) {
      EXPECT_EQ(last.trajectory[i].pose.x, kept.trajectory[i].pose.x) << pose_graph;
      EXPECT_EQ(last.trajectory[i].pose.theta, kept.trajectory[i].pose.theta) << pose_graph;
    }
    EXPECT_EQ(GridToMapImage(last.map).cells, GridToMapImage(kept.map).cells) << pose_graph;
    EXPECT_EQ(last.every_scan.matched, kept.every_scan.matched);
  }
}

// Following the pose graph moves every particle, its newest nodes and nothing else by the
// correction, and gives all of them the graph's map and history.
TEST(RbpfSlamTest, FollowingMovesEveryParticleByTheCorrection) {
  const testing::SimulatedRun run = testing::SimulateRoomRun(0.2);
  RbpfSlam slam(SmallFilter(6));
  for (std::size_t i = 0; i < 80; ++i) slam.AddScan(run.scans[i], static_cast<int>(i));
  const std::vector<Particle> before = slam.particles();
  const Pose2 correction(0.4, -0.3, 0.05);
  auto map = std::make_shared<OccupancyGrid>(OccupancyGridOptions{});
  auto history = std::make_shared<const TrajectoryNode>(TrajectoryNode{Pose2(1, 2, 3), 7, nullptr});
  slam.Follow(correction, map, history, 2);
  ASSERT_EQ(slam.particles().size(), before.size());
  for (std::size_t k = 0; k < before.size(); ++k) {
    const Particle& p = slam.particles()[k];
    const Pose2 expected = correction * before[k].pose;
    EXPECT_DOUBLE_EQ(p.pose.x, expected.x);
    EXPECT_DOUBLE_EQ(p.pose.y, expected.y);
    EXPECT_DOUBLE_EQ(p.pose.theta, expected.theta);
    EXPECT_EQ(p.map, map);
    EXPECT_EQ(p.log_weight, before[k].log_weight);
    const TrajectoryNode* newest = p.trajectory.get();
    const TrajectoryNode* old_newest = before[k].trajectory.get();
    for (int n = 0; n < 2; ++n) {
      const Pose2 moved = correction * old_newest->pose;
      EXPECT_DOUBLE_EQ(newest->pose.x, moved.x);
      EXPECT_DOUBLE_EQ(newest->pose.theta, moved.theta);
      EXPECT_EQ(newest->scan_index, old_newest->scan_index);
      newest = newest->parent.get();
      old_newest = old_newest->parent.get();
    }
    EXPECT_EQ(newest, history.get());
  }
}

// A turn in place of 1.2 rad in 0.1 rad steps among clutter, whose wheel odometry stalls for the
// first 0.4 rad and then reports the rest: at every processed scan the odometry is 0.4 rad behind.
std::vector<StampedScan> TurnWithStalledOdometry(std::vector<Pose2>* truth) {
  const auto world = testing::ClutteredWorld();
  std::vector<StampedScan> scans;
  for (int i = 0; i <= 12; ++i) {
    const Pose2 pose(0.3, -0.2, 0.1 * i);
    const Pose2 odometry(0.3, -0.2, std::max(0.0, 0.1 * i - 0.4));
    scans.push_back({testing::SimulateScan(world, pose), odometry, odometry});
    truth->push_back(pose);
  }
  return scans;
}

TEST(RbpfSlamTest, WheelOdometryThatStallsOnATurnIsCorrectedByTheScans) {
  std::vector<Pose2> truth;
  const std::vector<StampedScan> scans = TurnWithStalledOdometry(&truth);
  for (const bool sweep : {true, false}) {
    RbpfOptions options = SmallFilter(8);
    options.angular_update_radians = 0.5;
    options.motion = {0.1, 0.1, 0.2, 0.2};  // config/slam-gmapping.yaml
    options.proposal.heading_search.window_sigmas = sweep ? 5.0 : 0.0;
    RbpfSlam slam(options);
    for (std::size_t i = 0; i < scans.size(); ++i) slam.AddScan(scans[i], static_cast<int>(i));
    const TrajectoryNode* last = slam.BestParticle().trajectory.get();
    const double error = AngleDifference(last->pose.theta, truth[last->scan_index].theta);
    if (sweep) {
      EXPECT_NEAR(error, 0.0, DegToRad(1.0));
    } else {
      // Without the sweep the match cannot reach the heading (8° off here).
      EXPECT_GT(std::abs(error), DegToRad(3.0));
    }
  }
}

// TurnWithStalledOdometry without the heading sweep (config/slam-gmapping.yaml has none): no
// particle's hill climbing reaches the heading, every match is untrusted, and the proposal falls
// back on the motion model. The recovery search around each prediction (ACES's loop closure at
// its central crossing) finds the scan's heading.
TEST(RbpfSlamTest, WhenNoParticleMatchesARecoverySearchFindsTheScan) {
  std::vector<Pose2> truth;
  const std::vector<StampedScan> scans = TurnWithStalledOdometry(&truth);
  auto heading_error = [&](double recovery_window, int* recoveries) {
    RbpfOptions options = SmallFilter(8);
    options.angular_update_radians = 0.5;
    options.motion = {0.1, 0.1, 0.2, 0.2};  // config/slam-gmapping.yaml
    options.proposal.recovery_window_meters = recovery_window;
    RbpfSlam slam(options);
    for (std::size_t i = 0; i < scans.size(); ++i) slam.AddScan(scans[i], static_cast<int>(i));
    *recoveries = slam.statistics().recoveries;
    const TrajectoryNode* last = slam.BestParticle().trajectory.get();
    return std::abs(AngleDifference(last->pose.theta, truth[last->scan_index].theta));
  };
  int recoveries = 0;
  EXPECT_GT(heading_error(0.0, &recoveries), DegToRad(3.0));
  EXPECT_EQ(recoveries, 0);
  EXPECT_LT(heading_error(1.0, &recoveries), DegToRad(1.0));
  EXPECT_GE(recoveries, 1);
}

// The basic RBPF (no scan matching) trusts no match in any step; the recovery has no match to
// start and must not search (it did, in every step, for nothing).
TEST(RbpfSlamTest, WithoutScanMatchingThereIsNothingToRecover) {
  std::vector<Pose2> truth;
  const std::vector<StampedScan> scans = TurnWithStalledOdometry(&truth);
  RbpfOptions options = SmallFilter(4);
  options.angular_update_radians = 0.5;
  options.proposal.use_scan_matching = false;
  options.proposal.recovery_window_meters = 1.0;
  RbpfSlam slam(options);
  for (std::size_t i = 0; i < scans.size(); ++i) slam.AddScan(scans[i], static_cast<int>(i));
  ASSERT_GE(slam.statistics().processed, 2);
  EXPECT_EQ(slam.statistics().unmatched, 4 * (slam.statistics().processed - 1));
  EXPECT_EQ(slam.statistics().recoveries, 0);
}

// Where the scans constrain nothing (here: no returns at all) the proposal is the motion model,
// so the particles spread as it says. Driving 1 m in ten 0.1 m readings, GMapping's per-reading
// noise gives σ_θ = 0.2 · 0.1 · √10 = 0.063 rad, √10 times less than the 0.2 rad of one draw
// over the metre.
TEST(RbpfSlamTest, ParticlesSpreadAsTheReadingsNoiseWhereScansSayNothing) {
  const std::vector<testing::Segment> nothing;
  auto heading_spread = [&](bool per_reading) {
    RbpfOptions options = SmallFilter(400);
    options.linear_update_meters = 1.0;
    options.angular_update_radians = 0.5;
    options.motion = {0.1, 0.1, 0.2, 0.2};
    options.motion.per_reading_noise = per_reading;
    RbpfSlam slam(options);
    for (int i = 0; i <= 10; ++i) {
      const Pose2 odometry(0.1 * i, 0.0, 0.0);
      slam.AddScan({testing::SimulateScan(nothing, odometry), odometry, odometry}, i);
    }
    EXPECT_EQ(slam.statistics().processed, 2);
    double sum_squares = 0.0;
    for (const Particle& p : slam.particles()) sum_squares += p.pose.theta * p.pose.theta;
    return std::sqrt(sum_squares / static_cast<double>(slam.particles().size()));
  };
  const double per_reading = heading_spread(true), one_draw = heading_spread(false);
  // The Gaussian fitted to 17 weighted samples of a ±3σ window shrinks both by the same factor
  // (about 0.7), so their ratio is the figure to check.
  EXPECT_NEAR(per_reading / one_draw, 1.0 / std::sqrt(10.0), 0.05);
  EXPECT_GT(one_draw, 0.5 * 0.2);
  EXPECT_LT(one_draw, 0.2);
}

TEST(ScanLocalizerTest, InterpolationReanchorsOdometryOnCorrectedScans) {
  // Odometry with a constant offset; the corrected poses remove it, linearly in time between.
  const std::vector<Pose2> odometry = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  const std::vector<double> times = {0, 1, 2, 3};
  const std::vector<Pose2> poses =
      InterpolateTrajectory(odometry, times, {{0, Pose2(0, 1, 0)}, {2, Pose2(2, 3, 0)}});
  EXPECT_NEAR(poses[0].y, 1.0, 1e-12);
  EXPECT_NEAR(poses[1].y, 2.0, 1e-12);
  EXPECT_NEAR(poses[2].y, 3.0, 1e-12);
  EXPECT_NEAR(poses[3].y, 3.0, 1e-12);  // after the last corrected scan: its correction
  EXPECT_NEAR(poses[3].x, 3.0, 1e-12);
}

TEST(ScanLocalizerTest, InterpolationDoesNotDependOnWhereTheOdometryFrameIs) {
  // A turn whose odometry heading is off by 0.4 rad at the second processed scan (wheel odometry
  // on a fast turn): the scans between must lie between the two corrected poses, wherever the
  // odometry frame's origin is. The old global-correction interpolation put the middle scan
  // metres away once the odometry was 500 m from its origin.
  const std::vector<double> times = {0, 1, 2};
  const std::vector<std::pair<int, Pose2>> corrected = {{0, Pose2(0, 0, 0)}, {2, Pose2(1, 0, 0.5)}};
  const std::vector<Pose2> local = {{0, 0, 0}, {0.5, 0, 0.45}, {1, 0, 0.9}};
  for (const Pose2& frame : {Pose2(0, 0, 0), Pose2(500, -300, 2.0)}) {
    std::vector<Pose2> odometry;
    for (const Pose2& pose : local) odometry.push_back(frame * pose);
    const std::vector<Pose2> poses = InterpolateTrajectory(odometry, times, corrected);
    EXPECT_NEAR(poses[0].x, 0.0, 1e-9);
    EXPECT_NEAR(poses[2].x, 1.0, 1e-9);
    EXPECT_NEAR(poses[2].theta, 0.5, 1e-9);
    // Forward from scan 0: (0.5, 0, 0.45); backward from scan 2: (1, 0, 0.5) ⊕ (-0.5 rotated
    // back by 0.45 rad); their midpoint lies within a few centimetres of (0.5, 0).
    EXPECT_NEAR(poses[1].x, 0.5, 0.1);
    EXPECT_NEAR(poses[1].y, 0.0, 0.15);
    EXPECT_NEAR(poses[1].theta, 0.25, 1e-9);
  }
}

}  // namespace
}  // namespace semchain::mapping
