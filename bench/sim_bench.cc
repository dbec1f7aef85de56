// Simulated lidar throughput: scans per second (items_per_second) for a 360-beam lidar along the
// mapping route of worlds/two_similar_rooms.yaml, and the cost of a whole run without frames.
//   build/bench/sim_bench --benchmark_filter=Lidar
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

#include "core/rng.h"
#include "sim/lidar.h"
#include "sim/route_follower.h"
#include "sim/scene.h"
#include "sim/simulator.h"
#include "sim/world_io.h"

namespace semchain::sim {
namespace {

World LoadBenchWorld() {
  const auto world =
      LoadWorld(std::filesystem::path(SEMCHAIN_SOURCE_DIR) / "worlds" / "two_similar_rooms.yaml");
  if (!world.ok()) std::abort();
  return *world;
}

// Scans along the mapping route, cycling through its poses; Arg = beams over 360°.
void BM_LidarScan(benchmark::State& state) {
  World world = LoadBenchWorld();
  world.robot.lidar.beams = static_cast<int>(state.range(0));
  const Scene scene(world);
  const auto samples = GenerateTrajectory(scene, world.robot, RouteSpec{}, world.robot.start);
  if (!samples.ok()) std::abort();
  Rng rng = MakeRng(1, 1);
  std::size_t i = 0;
  for (auto _ : state) {
    const TrajectorySample& sample = (*samples)[i];
    benchmark::DoNotOptimize(SimulateScan(scene, world.robot.lidar, sample.pose, sample.time, rng));
    i = (i + 1) % samples->size();
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel("scans");
}
BENCHMARK(BM_LidarScan)->Arg(360)->Arg(1080);

// A whole mapping run without frames (trajectory, lidar, odometry, log and truth files).
void BM_SimulateMappingRunWithoutFrames(benchmark::State& state) {
  const World world = LoadBenchWorld();
  SimulationOptions options;
  options.write_frames = false;
  options.show_progress = false;
  const auto dir = std::filesystem::temp_directory_path() / "semchain_sim_bench_run";
  for (auto _ : state) {
    if (!Simulate(world, options, dir).ok()) std::abort();
  }
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_SimulateMappingRunWithoutFrames)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace semchain::sim

BENCHMARK_MAIN();
