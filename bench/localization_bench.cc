// Throughput of localization (DESIGN.md §6): one AMCL update with 5000 particles and 60 beams on
// the likelihood field, and branch-and-bound scan matching on a real map (the FR079 corrected
// log's map, built from its corrected poses; the synthetic room when the data is missing).
//   build/bench/localization_bench --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>

#include "eval/log_localization_trials.h"
#include "io/carmen.h"
#include "localization/amcl.h"
#include "localization/scan_match_relocalizer.h"
#include "mapping/slam_pipeline.h"
#include "mapping/testing/synthetic_map.h"

namespace semchain::localization {
namespace {

// A map and a scan with its true pose.
struct Scene {
  std::string name;
  mapping::MapImage map;
  StampedScan scan;
};

const Scene& GetScene() {
  static const std::unique_ptr<Scene> scene = [] {
    auto s = std::make_unique<Scene>();
    const std::filesystem::path log_path = std::filesystem::path(SEMCHAIN_SOURCE_DIR) /
                                           "../shared/data/fr079/freiburg-079-corrected.log.gz";
    const Result<carmen::Log> log = carmen::ReadLog(log_path);
    if (log.ok()) {
      const Result<std::vector<StampedScan>> scans = mapping::ScansFromLog(*log, "fr079");
      if (scans.ok()) {
        s->name = "fr079";
        s->map = eval::MapFromCorrectedPoses(*scans, 0.05, 30.0);
        s->scan = (*scans)[scans->size() / 3];
        return s;
      }
    }
    s->name = "synthetic room";
    s->map = mapping::testing::RoomMap();
    const Pose2 truth(0.37, -0.21, 0.3);
    s->scan.scan = mapping::testing::SimulateScan(mapping::testing::RoomWorld(), truth);
    s->scan.odometry = s->scan.laser_pose = truth;
    return s;
  }();
  return *scene;
}

// One whole filter update (motion, 60-beam likelihood field for every particle, KLD
// resampling, clustering) of state.range(0) particles around the true pose (5000: the speed
// target's figure; 20000: nav2 protocol's max_particles).
void BM_AmclUpdate60Beams(benchmark::State& state) {
  const Scene& scene = GetScene();
  const int particles = static_cast<int>(state.range(0));
  AmclOptions options;
  options.min_particles = options.max_particles = particles;
  const LocalizationMap map(scene.map, options.laser_likelihood_max_dist);
  Amcl amcl(map, options, MakeRng(1));
  amcl.InitializePose(scene.scan.odometry, Eigen::Vector3d(0.01, 0.01, 0.003).asDiagonal());
  Pose2 odometry = scene.scan.odometry;
  bool forward = true;
  for (auto _ : state) {
    // Alternate ±0.3 m so that every call passes update_min_d and updates the filter.
    odometry = odometry * Pose2(forward ? 0.3 : -0.3, 0.0, 0.0);
    forward = !forward;
    benchmark::DoNotOptimize(amcl.ProcessScan(scene.scan.scan, odometry, scene.scan.LaserOffset()));
  }
  state.SetItemsProcessed(state.iterations() * particles);  // particle updates
  state.SetLabel(scene.name);
}
BENCHMARK(BM_AmclUpdate60Beams)->Arg(5000)->Arg(20000)->Unit(benchmark::kMillisecond);

// The likelihood-field weight alone, 5000 particles × 60 beams.
void BM_LikelihoodFieldWeights5000(benchmark::State& state) {
  const Scene& scene = GetScene();
  const AmclOptions options;
  const LocalizationMap map(scene.map, options.laser_likelihood_max_dist);
  const LikelihoodFieldModel model(map, options);
  const LaserBeams beams = SelectBeams(scene.scan.scan, scene.scan.LaserOffset(), options);
  Rng rng = MakeRng(2);
  std::vector<Pose2> poses;
  PoseHypothesis h;
  h.pose = scene.scan.odometry;
  for (int i = 0; i < 5000; ++i) poses.push_back(SamplePose(h, rng));
  for (auto _ : state) {
    double sum = 0.0, mean = 0.0;
    for (const Pose2& pose : poses) sum += model.Weight(beams, pose, &mean);
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * 5000);
  state.counters["beams"] = static_cast<double>(beams.ranges.size());
}
BENCHMARK(BM_LikelihoodFieldWeights5000)->Unit(benchmark::kMillisecond);

// Global relocalization: branch-and-bound over the whole map and every heading, then Ceres.
void BM_BranchAndBoundGlobal(benchmark::State& state) {
  const Scene& scene = GetScene();
  const ScanMatchRelocalizer relocalizer(scene.map, {});
  RelocalizationResult result;
  for (auto _ : state) {
    result = relocalizer.RelocalizeGlobal(scene.scan.scan, scene.scan.LaserOffset());
    benchmark::DoNotOptimize(result);
  }
  state.SetLabel(scene.name);
  state.counters["nodes"] = static_cast<double>(result.nodes_scored);
  state.counters["angles"] = result.angles;
  state.counters["points"] = result.points;
  state.counters["score"] = result.score;
  state.counters["error_m"] =
      (result.pose.translation() - scene.scan.odometry.translation()).norm();
}
BENCHMARK(BM_BranchAndBoundGlobal)->Unit(benchmark::kMillisecond);

// Global relocalization on the MIT Killian map (250 m × 245 m, mostly unknown space around the
// corridors), one scan a third into the log: state.range(0) = 0 searches every translation (as
// before the free-space restriction), 1 only those within 0.25 m of free space (the default).
void BM_BranchAndBoundGlobalKillian(benchmark::State& state) {
  static const std::unique_ptr<Scene> killian = [] {
    auto s = std::make_unique<Scene>();
    const std::filesystem::path log_path =
        std::filesystem::path(SEMCHAIN_SOURCE_DIR) /
        "../shared/data/mit-killian/infinite-corridor-corrected.log.gz";
    const Result<carmen::Log> log = carmen::ReadLog(log_path);
    if (!log.ok()) return std::unique_ptr<Scene>();
    const Result<std::vector<StampedScan>> scans = mapping::ScansFromLog(*log, "killian");
    if (!scans.ok()) return std::unique_ptr<Scene>();
    s->name = "killian";
    s->map = eval::MapFromCorrectedPoses(*scans, 0.05, 30.0);
    s->scan = (*scans)[scans->size() / 3];
    return s;
  }();
  if (!killian) {
    state.SkipWithError("the MIT Killian corrected log is missing");
    return;
  }
  ScanMatchRelocalizerOptions options;
  if (state.range(0) == 0) options.global_free_space_margin_meters = -1.0;
  if (state.range(1) > 0)
    options.branch_and_bound.branch_and_bound_depth = static_cast<int>(state.range(1));
  const ScanMatchRelocalizer relocalizer(killian->map, options);
  RelocalizationResult result;
  for (auto _ : state) {
    result = relocalizer.RelocalizeGlobal(killian->scan.scan, killian->scan.LaserOffset());
    benchmark::DoNotOptimize(result);
  }
  state.SetLabel(state.range(0) == 0 ? "whole map" : "free space");
  state.counters["roots"] = static_cast<double>(result.root_nodes);
  state.counters["nodes"] = static_cast<double>(result.nodes_scored);
  state.counters["angles"] = result.angles;
  state.counters["score"] = result.score;
  state.counters["error_m"] =
      (result.pose.translation() - killian->scan.odometry.translation()).norm();
}
BENCHMARK(BM_BranchAndBoundGlobalKillian)
    ->Args({0, 0})
    ->Args({1, 0})
    ->Unit(benchmark::kMillisecond);

// Relocalization with a prior: a ±1 m, ±0.5 rad window around a pose 0.4 m / 0.2 rad off.
void BM_BranchAndBoundWithPrior(benchmark::State& state) {
  const Scene& scene = GetScene();
  const ScanMatchRelocalizer relocalizer(scene.map, {});
  PoseHypothesis prior;
  prior.pose = scene.scan.odometry * Pose2(0.3, -0.25, 0.2);
  prior.covariance = Eigen::Vector3d(0.11, 0.11, 0.028).asDiagonal();
  RelocalizationResult result;
  for (auto _ : state) {
    result = relocalizer.Relocalize(scene.scan.scan, scene.scan.LaserOffset(), {prior});
    benchmark::DoNotOptimize(result);
  }
  state.counters["nodes"] = static_cast<double>(result.nodes_scored);
  state.counters["error_m"] =
      (result.pose.translation() - scene.scan.odometry.translation()).norm();
}
BENCHMARK(BM_BranchAndBoundWithPrior)->Unit(benchmark::kMillisecond);

// The branch-and-bound search alone in the narrow window a semantic prior gets first (±0.3 m,
// ±0.07 rad) around a pose 0.1 m / 0.03 rad off.
void BM_BranchAndBoundNarrowWindow(benchmark::State& state) {
  const Scene& scene = GetScene();
  const ScanMatchRelocalizerOptions options;
  const ScanMatchRelocalizer relocalizer(scene.map, options);
  const mapping::BranchAndBoundMatcher matcher(relocalizer.grid(), options.branch_and_bound);
  const std::vector<Eigen::Vector2d> points =
      relocalizer.MatchPoints(scene.scan.scan, scene.scan.LaserOffset());
  mapping::SearchWindow window;
  window.center = scene.scan.odometry * Pose2(0.08, -0.06, 0.03);
  window.linear_window_meters = options.narrow_linear_window_meters;
  window.angular_window_radians = options.narrow_angular_window_radians;
  mapping::BranchAndBoundResult result;
  for (auto _ : state) {
    result = matcher.Match(points, window, options.min_score);
    benchmark::DoNotOptimize(result);
  }
  state.SetLabel(scene.name);
  state.counters["nodes"] = static_cast<double>(result.nodes_scored);
  state.counters["angles"] = result.angles;
  state.counters["points"] = static_cast<double>(points.size());
  state.counters["error_m"] =
      (result.pose.translation() - scene.scan.odometry.translation()).norm();
}
BENCHMARK(BM_BranchAndBoundNarrowWindow)->Unit(benchmark::kMicrosecond);

// Ceres refinement (seed 001 §2.2) of the scan from a pose one cell and one angular step off,
// as it follows every branch-and-bound match.
void BM_CeresRefinement(benchmark::State& state) {
  const Scene& scene = GetScene();
  const ScanMatchRelocalizer relocalizer(scene.map, {});
  const std::vector<Eigen::Vector2d> points =
      relocalizer.MatchPoints(scene.scan.scan, scene.scan.LaserOffset());
  const Pose2 start = scene.scan.odometry * Pose2(0.05, -0.05, 0.005);
  mapping::CeresMatchResult result;
  for (auto _ : state) {
    result = mapping::RefineWithCeres(relocalizer.grid(), points, start, {});
    benchmark::DoNotOptimize(result);
  }
  state.SetLabel(scene.name);
  state.counters["points"] = static_cast<double>(points.size());
  state.counters["iterations"] = result.iterations;
  state.counters["error_m"] =
      (result.pose.translation() - scene.scan.odometry.translation()).norm();
}
BENCHMARK(BM_CeresRefinement)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace semchain::localization

BENCHMARK_MAIN();
