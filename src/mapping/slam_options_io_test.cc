#include "mapping/slam_options_io.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace semchain::mapping {
namespace {

const std::filesystem::path kConfigDir = std::filesystem::path(SEMCHAIN_SOURCE_DIR) / "config";

TEST(SlamOptionsIoTest, ShippedDefaultsFileMatchesTheBuiltInDefaults) {
  SlamOptions loaded;
  loaded.rbpf.particles = 7;  // the file must set it back
  loaded.every_scan.refinement.iterations = 1;
  loaded.every_scan.search_below_ratio = 0.0;
  loaded.every_scan.search.angular_window_radians = 0.0;
  loaded.every_scan.prior_sigma_meters = 0.0;
  const Status status = LoadSlamOptions(kConfigDir / "slam.yaml", &loaded);
  ASSERT_TRUE(status.ok()) << status.message();
  const SlamOptions defaults;
  EXPECT_EQ(loaded.rbpf.particles, defaults.rbpf.particles);
  EXPECT_EQ(loaded.rbpf.match_beam_step, defaults.rbpf.match_beam_step);
  EXPECT_DOUBLE_EQ(loaded.rbpf.weight_gain, defaults.rbpf.weight_gain);
  EXPECT_DOUBLE_EQ(loaded.rbpf.field.likelihood_sigma_meters,
                   defaults.rbpf.field.likelihood_sigma_meters);
  EXPECT_DOUBLE_EQ(loaded.rbpf.proposal.sample_window_radians,
                   defaults.rbpf.proposal.sample_window_radians);
  EXPECT_DOUBLE_EQ(loaded.rbpf.proposal.recovery_window_meters,
                   defaults.rbpf.proposal.recovery_window_meters);
  EXPECT_DOUBLE_EQ(loaded.rbpf.proposal.recovery_window_radians,
                   defaults.rbpf.proposal.recovery_window_radians);
  EXPECT_DOUBLE_EQ(loaded.rbpf.genetic.beta, defaults.rbpf.genetic.beta);
  EXPECT_EQ(loaded.every_scan.refinement.iterations, defaults.every_scan.refinement.iterations);
  EXPECT_EQ(loaded.laser_odometry.scans_per_submap, defaults.laser_odometry.scans_per_submap);
  EXPECT_DOUBLE_EQ(loaded.laser_odometry.refinement.max_correction_meters,
                   defaults.laser_odometry.refinement.max_correction_meters);
  EXPECT_DOUBLE_EQ(loaded.laser_odometry.prior.min_rotation_sigma_radians,
                   defaults.laser_odometry.prior.min_rotation_sigma_radians);
  EXPECT_EQ(loaded.every_scan.refinement.lines_only, defaults.every_scan.refinement.lines_only);
  EXPECT_DOUBLE_EQ(loaded.every_scan.search_below_ratio, defaults.every_scan.search_below_ratio);
  EXPECT_EQ(loaded.every_scan.typical_window_scans, defaults.every_scan.typical_window_scans);
  EXPECT_DOUBLE_EQ(loaded.every_scan.search_margin_ratio, defaults.every_scan.search_margin_ratio);
  EXPECT_DOUBLE_EQ(loaded.every_scan.search.angular_window_radians,
                   defaults.every_scan.search.angular_window_radians);
  EXPECT_DOUBLE_EQ(loaded.every_scan.search.linear_window_meters,
                   defaults.every_scan.search.linear_window_meters);
  EXPECT_DOUBLE_EQ(loaded.every_scan.prior_sigma_meters, defaults.every_scan.prior_sigma_meters);
  EXPECT_DOUBLE_EQ(loaded.every_scan.prior_sigma_radians, defaults.every_scan.prior_sigma_radians);
  EXPECT_EQ(loaded.rbpf.motion.per_reading_noise, defaults.rbpf.motion.per_reading_noise);
  EXPECT_EQ(loaded.pose_graph, defaults.pose_graph);
  const LoopClosureOptions& l = loaded.loop_closure;
  const LoopClosureOptions& d = defaults.loop_closure;
  EXPECT_DOUBLE_EQ(l.submap_travel_meters, d.submap_travel_meters);
  EXPECT_DOUBLE_EQ(l.min_loop_travel_meters, d.min_loop_travel_meters);
  EXPECT_EQ(l.search_every_nodes, d.search_every_nodes);
  EXPECT_EQ(l.max_built_submaps, d.max_built_submaps);
  EXPECT_DOUBLE_EQ(l.max_built_submaps_megabytes, d.max_built_submaps_megabytes);
  EXPECT_DOUBLE_EQ(l.linear_window_meters, d.linear_window_meters);
  EXPECT_DOUBLE_EQ(l.window_sigmas, d.window_sigmas);
  EXPECT_DOUBLE_EQ(l.gate_sigmas, d.gate_sigmas);
  EXPECT_DOUBLE_EQ(l.confirm_within_meters, d.confirm_within_meters);
  EXPECT_EQ(l.confirm_every_closure, d.confirm_every_closure);
  EXPECT_EQ(l.corridor_confirmation, d.corridor_confirmation);
  EXPECT_DOUBLE_EQ(l.confirm_min_separation_meters, d.confirm_min_separation_meters);
  EXPECT_EQ(l.unknown_is_neutral, d.unknown_is_neutral);
  EXPECT_DOUBLE_EQ(l.min_known_fraction, d.min_known_fraction);
  EXPECT_EQ(l.match_covariance, d.match_covariance);
  EXPECT_DOUBLE_EQ(l.covariance.window_meters, d.covariance.window_meters);
  EXPECT_DOUBLE_EQ(l.covariance.window_radians, d.covariance.window_radians);
  EXPECT_DOUBLE_EQ(l.covariance.score_drop, d.covariance.score_drop);
  EXPECT_DOUBLE_EQ(l.query_travel_meters, d.query_travel_meters);
  EXPECT_DOUBLE_EQ(l.query_cell_meters, d.query_cell_meters);
  EXPECT_DOUBLE_EQ(l.max_linear_window_meters, d.max_linear_window_meters);
  EXPECT_DOUBLE_EQ(l.angular_window_radians, d.angular_window_radians);
  EXPECT_DOUBLE_EQ(l.odometry_sigma_meters, d.odometry_sigma_meters);
  EXPECT_DOUBLE_EQ(l.odometry_sigma_per_meter, d.odometry_sigma_per_meter);
  EXPECT_DOUBLE_EQ(l.odometry_sigma_radians, d.odometry_sigma_radians);
  EXPECT_DOUBLE_EQ(l.odometry_sigma_radians_per_radian, d.odometry_sigma_radians_per_radian);
  EXPECT_DOUBLE_EQ(l.max_angular_window_radians, d.max_angular_window_radians);
  EXPECT_DOUBLE_EQ(l.min_score, d.min_score);
  EXPECT_EQ(l.min_points, d.min_points);
  EXPECT_DOUBLE_EQ(l.match_max_range_meters, d.match_max_range_meters);
  EXPECT_EQ(l.match_beam_step, d.match_beam_step);
  EXPECT_DOUBLE_EQ(l.loop_sigma_meters, d.loop_sigma_meters);
  EXPECT_DOUBLE_EQ(l.loop_sigma_radians, d.loop_sigma_radians);
  EXPECT_DOUBLE_EQ(l.snap_sigmas, d.snap_sigmas);
  EXPECT_EQ(l.adapt_motion_noise, d.adapt_motion_noise);
  EXPECT_DOUBLE_EQ(l.min_motion_noise_scale, d.min_motion_noise_scale);
  EXPECT_DOUBLE_EQ(l.max_motion_noise_scale, d.max_motion_noise_scale);
  EXPECT_DOUBLE_EQ(l.max_residual_sigmas, d.max_residual_sigmas);
  EXPECT_EQ(l.optimizer.loop_loss, d.optimizer.loop_loss);
  EXPECT_DOUBLE_EQ(l.optimizer.loop_loss_scale, d.optimizer.loop_loss_scale);
  EXPECT_DOUBLE_EQ(l.optimizer.dcs_phi, d.optimizer.dcs_phi);
  EXPECT_EQ(l.online, d.online);
  EXPECT_EQ(l.online_lag_nodes, d.online_lag_nodes);
  EXPECT_EQ(l.background, d.background);
  EXPECT_DOUBLE_EQ(l.follow_min_shift_meters, d.follow_min_shift_meters);
  EXPECT_DOUBLE_EQ(l.follow_min_turn_radians, d.follow_min_turn_radians);
}

TEST(SlamOptionsIoTest, EveryShippedSlamConfigLoads) {
  for (const auto& entry : std::filesystem::directory_iterator(kConfigDir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("slam", 0) != 0 || entry.path().extension() != ".yaml") continue;
    SlamOptions options;
    const Status status = LoadSlamOptions(entry.path(), &options);
    EXPECT_TRUE(status.ok()) << name << ": " << status.message();
  }
  SlamOptions gmapping;
  ASSERT_TRUE(LoadSlamOptions(kConfigDir / "slam-gmapping.yaml", &gmapping).ok());
  EXPECT_FALSE(gmapping.laser_odometry.enabled);
  EXPECT_DOUBLE_EQ(gmapping.rbpf.proposal.recovery_window_meters, 1.0);
  SlamOptions campus;
  ASSERT_TRUE(LoadSlamOptions(kConfigDir / "slam-campus.yaml", &campus).ok());
  EXPECT_TRUE(campus.pose_graph);
  EXPECT_TRUE(campus.loop_closure.unknown_is_neutral);
  EXPECT_TRUE(campus.loop_closure.confirm_every_closure);
  EXPECT_TRUE(campus.loop_closure.corridor_confirmation);
  EXPECT_DOUBLE_EQ(campus.loop_closure.query_travel_meters, 10.0);
  EXPECT_DOUBLE_EQ(campus.rbpf.motion.translation_per_meter, 0.02);
  EXPECT_DOUBLE_EQ(campus.rbpf.motion.translation_per_radian, 0.02);
}

TEST(SlamOptionsIoTest, UnknownKeysAndBadValuesAreErrors) {
  SlamOptions options;
  Result<yaml::Node> root =
      yaml::Node::LoadString("particles: 10\ngenetic:\n  crosover_rate_1: 0.7\n", "c.yaml");
  ASSERT_TRUE(root.ok());
  Status status = ReadSlamOptions(*root, &options);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("c.yaml:3"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("crosover_rate_1"), std::string::npos);
  root = yaml::Node::LoadString("annealing: {rule: sometimes}\n", "d.yaml");
  status = ReadSlamOptions(*root, &options);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("rule"), std::string::npos) << status.message();
  root = yaml::Node::LoadString("pose_graph:\n  enabled: true\n  min_score: 1.5\n", "e.yaml");
  options = SlamOptions();
  status = ReadSlamOptions(*root, &options);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("pose_graph.min_score"), std::string::npos) << status.message();
  root = yaml::Node::LoadString("proposal: {recovery_window_meters: -1}\n", "g.yaml");
  options = SlamOptions();
  status = ReadSlamOptions(*root, &options);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("recovery_window_meters"), std::string::npos) << status.message();
  root = yaml::Node::LoadString("pose_graph: {enabled: true, windw: 3}\n", "f.yaml");
  options = SlamOptions();
  status = ReadSlamOptions(*root, &options);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("windw"), std::string::npos) << status.message();
}

TEST(SlamOptionsIoTest, TheLoopClosureLossByName) {
  SlamOptions options;
  Result<yaml::Node> root =
      yaml::Node::LoadString("pose_graph: {loop_loss: dcs, dcs_phi: 2.5}\n", "a.yaml");
  ASSERT_TRUE(root.ok());
  ASSERT_TRUE(ReadSlamOptions(*root, &options).ok());
  EXPECT_EQ(options.loop_closure.optimizer.loop_loss, RobustLoss::kDynamicCovarianceScaling);
  EXPECT_DOUBLE_EQ(options.loop_closure.optimizer.dcs_phi, 2.5);
  root = yaml::Node::LoadString("pose_graph: {loop_loss: huber}\n", "b.yaml");
  ASSERT_TRUE(ReadSlamOptions(*root, &options).ok());
  EXPECT_EQ(options.loop_closure.optimizer.loop_loss, RobustLoss::kHuber);
  root =
      yaml::Node::LoadString("pose_graph:\n  enabled: true\n  loop_loss: switchable\n", "c.yaml");
  const Status status = ReadSlamOptions(*root, &options);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("c.yaml:3"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("switchable"), std::string::npos) << status.message();
}

TEST(SlamOptionsIoTest, VariantsSwitchTheImprovements) {
  SlamOptions options;
  ASSERT_TRUE(ApplyVariant("both", &options).ok());
  EXPECT_TRUE(options.rbpf.annealing.enabled && options.rbpf.genetic.enabled);
  ASSERT_TRUE(ApplyVariant("plain", &options).ok());
  EXPECT_FALSE(options.rbpf.annealing.enabled || options.rbpf.genetic.enabled);
  ASSERT_TRUE(ApplyVariant("genetic", &options).ok());
  EXPECT_TRUE(options.rbpf.genetic.enabled && !options.rbpf.annealing.enabled);
  EXPECT_FALSE(ApplyVariant("fancy", &options).ok());
}

}  // namespace
}  // namespace semchain::mapping
