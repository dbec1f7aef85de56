// `semchain bench reloc` in small: map two_similar_rooms from a simulated mapping run
// (SLAM + semantic mapping), then relocalize from a few random starts in room A. The semantic
// methods must find the robot in every trial, and the first pre-localization must be close.
// Then the particle snapshots of `localize --png` on one trial, on maps made from the world's
// truth (quick): recording them changes nothing, and the cloud they show converges.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/angles.h"
#include "eval/reloc_benchmark.h"
#include "sim/world.h"
#include "testing/truth_maps.h"

namespace semchain {
namespace {

namespace fs = std::filesystem;

TEST(RelocBenchmarkTest, SemanticMethodsRelocalizeInLookAlikeRooms) {
  const fs::path world = fs::path(SEMCHAIN_SOURCE_DIR) / "worlds" / "two_similar_rooms.yaml";
  eval::RelocBenchmarkOptions options;
  options.trials = 4;
  options.seed = 7;
  options.methods = {"semantic-amcl", "semantic-scanmatch"};
  options.work_dir =
      fs::temp_directory_path() / ("semchain_reloc_e2e_" + std::to_string(::getpid()));
  const Result<eval::RelocBenchmarkResult> result = eval::RunRelocBenchmark(world, world, options);
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_LE(result->map_ate_m, 0.05);
  for (const std::string& method : options.methods) {
    const eval::RelocMethodStats& stats = result->methods.at(method);
    EXPECT_EQ(stats.trials, 4);
    EXPECT_EQ(stats.successes, 4) << method;
    EXPECT_LE(stats.mean_error_m, 0.1) << method;
    EXPECT_LE(stats.mean_time_s, 10.0) << method;
  }
  const eval::RelocMethodStats& amcl = result->methods.at("semantic-amcl");
  ASSERT_GT(amcl.prelocalized, 0);
  EXPECT_LE(amcl.prelocalization_error_x_m, 0.15);
  EXPECT_LE(amcl.prelocalization_error_y_m, 0.15);
  // The scan matcher searches only around the hypotheses: about one match per trial.
  EXPECT_LE(result->methods.at("semantic-scanmatch").mean_iterations, 2.0);
}

// Weighted RMS distance of the particles from their weighted mean, metres.
double Spread(const localization::ParticleSnapshot& snapshot) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  double total = 0.0;
  for (std::size_t i = 0; i < snapshot.poses.size(); ++i) {
    mean += snapshot.weights[i] * snapshot.poses[i].translation();
    total += snapshot.weights[i];
  }
  mean /= total;
  double sum = 0.0;
  for (std::size_t i = 0; i < snapshot.poses.size(); ++i) {
    sum += snapshot.weights[i] * (snapshot.poses[i].translation() - mean).squaredNorm();
  }
  return std::sqrt(sum / total);
}

// Particle snapshots (localize --png) only look: the trace is the same with and without them;
// and on a trial where semantic-amcl finds the robot, its cloud shrinks from the first
// snapshot (global initialisation) to the last.
TEST(RelocMethodsTest, ParticleSnapshotsChangeNothingAndShrink) {
  const fs::path world_path = fs::path(SEMCHAIN_SOURCE_DIR) / "worlds" / "two_similar_rooms.yaml";
  const Result<sim::World> world = sim::LoadWorld(world_path);
  ASSERT_TRUE(world.ok()) << world.status().message();
  const fs::path work =
      fs::temp_directory_path() / ("semchain_reloc_snapshots_" + std::to_string(::getpid()));
  eval::RelocBenchmarkOptions options;
  options.trial_turns = 1.0;  // a short trial: one turn in place, then up to 1 m ahead
  const Result<eval::RelocTrialRun> trial =
      eval::SimulateRelocTrial(*world, Pose2(2.1, 2.4, 0.0), 11, options, work);
  fs::remove_all(work);
  ASSERT_TRUE(trial.ok()) << trial.status().message();
  const e2e::TruthMaps maps = e2e::MapsFromTruth(*world);
  ASSERT_FALSE(maps.semantic.chains.empty());
  const localization::LocalizerMap map(maps.occupancy, maps.semantic, localization::AmclOptions(),
                                       localization::PreLocalizationOptions(),
                                       localization::ScanMatchRelocalizerOptions());

  eval::RelocRunInputs inputs = trial->inputs;
  const localization::RelocTrace plain =
      eval::RunRelocMethod(localization::LocalizationMethod::kSemanticAmcl, map,
                           localization::LocalizerOptions(), inputs);
  inputs.record_particles_every = 4;
  inputs.record_particles_max = 500;
  const localization::RelocTrace recorded =
      eval::RunRelocMethod(localization::LocalizationMethod::kSemanticAmcl, map,
                           localization::LocalizerOptions(), inputs);

  EXPECT_TRUE(plain.particle_snapshots.empty());
  ASSERT_EQ(plain.estimates.size(), recorded.estimates.size());
  for (std::size_t i = 0; i < plain.estimates.size(); ++i) {
    ASSERT_EQ(plain.estimates[i].has_value(), recorded.estimates[i].has_value()) << i;
    if (!plain.estimates[i]) continue;
    EXPECT_EQ(plain.estimates[i]->x, recorded.estimates[i]->x) << i;
    EXPECT_EQ(plain.estimates[i]->y, recorded.estimates[i]->y) << i;
    EXPECT_EQ(plain.estimates[i]->theta, recorded.estimates[i]->theta) << i;
  }
  EXPECT_EQ(plain.iterations, recorded.iterations);
  EXPECT_EQ(plain.prelocalization_scan, recorded.prelocalization_scan);
  EXPECT_EQ(plain.prelocalizations, recorded.prelocalizations);

  // The method succeeds on this trial.
  ASSERT_TRUE(recorded.estimates.back().has_value());
  const Pose2& truth = trial->truth.back().pose;
  EXPECT_LE((recorded.estimates.back()->translation() - truth.translation()).norm(), 0.25);
  EXPECT_LE(std::abs(NormalizeAngle(recorded.estimates.back()->theta - truth.theta)), 0.1745);

  const std::vector<localization::ParticleSnapshot>& snapshots = recorded.particle_snapshots;
  ASSERT_GE(snapshots.size(), 3u);
  for (std::size_t i = 0; i < snapshots.size(); ++i) {
    EXPECT_LE(snapshots[i].poses.size(), 500u);
    EXPECT_EQ(snapshots[i].poses.size(), snapshots[i].weights.size());
    if (i > 0) {
      EXPECT_LT(snapshots[i - 1].scan, snapshots[i].scan);
    }
  }
  // One snapshot is of the first filter update at or after the pre-localization the method
  // accepted, and the last is the last update.
  ASSERT_GE(recorded.prelocalization_scan, 0);
  const auto updated_at = [&](std::size_t k) {
    return recorded.iterations[k] > (k > 0 ? recorded.iterations[k - 1] : 0);
  };
  std::size_t first_update = static_cast<std::size_t>(recorded.prelocalization_scan);
  while (first_update < recorded.iterations.size() && !updated_at(first_update)) ++first_update;
  ASSERT_LT(first_update, recorded.iterations.size());
  EXPECT_TRUE(std::any_of(snapshots.begin(), snapshots.end(),
                          [&](const auto& s) { return s.scan == static_cast<int>(first_update); }));
  // semantic-amcl counts filter updates: the last is where the count last went up.
  const auto last_update =
      std::find(recorded.iterations.begin(), recorded.iterations.end(), recorded.iterations.back());
  EXPECT_EQ(snapshots.back().scan, static_cast<int>(last_update - recorded.iterations.begin()));
  EXPECT_GT(Spread(snapshots.front()), 2.0);  // uniform over the map
  EXPECT_LT(Spread(snapshots.back()), 0.1 * Spread(snapshots.front()));
  EXPECT_LT(Spread(snapshots.back()), 0.3);
}

}  // namespace
}  // namespace semchain
