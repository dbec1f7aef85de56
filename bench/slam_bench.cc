// Throughput of the SLAM building blocks (DESIGN.md §6: never a time limit in a unit test).
//   build-slam/bench/slam_bench --benchmark_min_time=0.5
#include <benchmark/benchmark.h>

#include "core/angles.h"
#include "mapping/hill_climbing_matcher.h"
#include "mapping/ray_casting.h"
#include "mapping/rbpf_slam.h"
#include "mapping/testing/synthetic_world.h"

namespace semchain::mapping {
namespace {

OccupancyGrid RoomMap() {
  const auto world = testing::RoomWorld();
  OccupancyGrid grid;
  for (const Pose2& pose : {Pose2(0, 0, 0), Pose2(-2, 1, kPi), Pose2(2, -1, kPi / 2)}) {
    InsertScan(PrepareScan(testing::SimulateScan(world, pose), Pose2(), {}), pose, &grid);
  }
  return grid;
}

void BM_LikelihoodFieldEvaluate(benchmark::State& state) {
  const OccupancyGrid grid = RoomMap();
  const LikelihoodField field(grid, {});
  const Pose2 truth(0.37, -0.21, 0.3);
  const MatchPoints points = SelectMatchPoints(
      PrepareScan(testing::SimulateScan(testing::RoomWorld(), truth), Pose2(), {}), 30.0);
  for (auto _ : state) benchmark::DoNotOptimize(field.Evaluate(points, truth));
  state.SetItemsProcessed(state.iterations());
  state.counters["points"] = static_cast<double>(points.size());
}
BENCHMARK(BM_LikelihoodFieldEvaluate);

// One scan match (hill climbing from a 5 cm / 3° error): matches per second.
void BM_HillClimbingMatch(benchmark::State& state) {
  const OccupancyGrid grid = RoomMap();
  const LikelihoodField field(grid, {});
  const Pose2 truth(0.37, -0.21, 0.3);
  const MatchPoints points = SelectMatchPoints(
      PrepareScan(testing::SimulateScan(testing::RoomWorld(), truth), Pose2(), {}), 30.0,
      static_cast<int>(state.range(0)));
  const Pose2 initial(truth.x + 0.04, truth.y - 0.03, truth.theta + 0.05);
  for (auto _ : state) benchmark::DoNotOptimize(HillClimb(field, points, initial, {}));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_HillClimbingMatch)->Arg(1)->Arg(2)->ArgName("beam_step");

void BM_InsertScan(benchmark::State& state) {
  const PreparedScan scan =
      PrepareScan(testing::SimulateScan(testing::RoomWorld(), Pose2()), Pose2(), {});
  OccupancyGrid grid;
  for (auto _ : state) InsertScan(scan, Pose2(), &grid);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_InsertScan);

// Processed scans of the RBPF on a simulated run: items = particle updates.
void BM_RbpfParticleUpdates(benchmark::State& state) {
  const testing::SimulatedRun run = testing::SimulateRoomRun(0.3, 0.01, 1);
  RbpfOptions options;
  options.particles = static_cast<int>(state.range(0));
  options.threads = static_cast<int>(state.range(1));
  options.linear_update_meters = 0.0;
  options.angular_update_radians = 0.0;
  std::int64_t updates = 0;
  for (auto _ : state) {
    RbpfSlam slam(options);
    for (std::size_t i = 0; i < run.scans.size(); ++i) {
      slam.AddScan(run.scans[i], static_cast<int>(i));
    }
    updates += static_cast<std::int64_t>(slam.statistics().processed - 1) * options.particles;
  }
  state.SetItemsProcessed(updates);
}
BENCHMARK(BM_RbpfParticleUpdates)
    ->Args({30, 1})
    ->Args({30, 2})
    ->ArgNames({"particles", "threads"})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace semchain::mapping

BENCHMARK_MAIN();
