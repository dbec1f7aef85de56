// Planning and depth-fusion throughput (DESIGN.md §6: measured here, never a time limit in a
// test): costmap construction and A* across a 2000 × 2000 map (100 m × 100 m at 0.05 m), and
// depth image → virtual scan conversion.
//   build/bench/plan_bench --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <random>

#include "core/angles.h"
#include "core/transforms.h"
#include "planning/astar.h"
#include "planning/costmap.h"
#include "sensors/depth_to_scan.h"

namespace semchain::planning {
namespace {

constexpr int kSize = 2000;

// A seeded 'size' × 'size' map of rectangular obstacles 0.5–3 m wide (about 12 % of the area),
// a building-sized test case; the corners where routes start and end are kept clear.
mapping::MapImage ObstacleField(int size, std::uint64_t seed) {
  mapping::MapImage map;
  map.width = map.height = size;
  map.resolution = 0.05;
  map.cells.assign(static_cast<std::size_t>(size) * size, 0);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> position(0, size - 1);
  std::uniform_int_distribution<int> extent(10, 60);
  const int boxes = size * size / 2500;
  for (int b = 0; b < boxes; ++b) {
    const int x0 = position(rng), y0 = position(rng), w = extent(rng), h = extent(rng);
    for (int y = y0; y < std::min(size, y0 + h); ++y) {
      for (int x = x0; x < std::min(size, x0 + w); ++x) {
        const bool corner = (x < 60 && y < 60) || (x >= size - 60 && y >= size - 60);
        if (!corner) map.cells[static_cast<std::size_t>(y) * size + x] = 100;
      }
    }
  }
  return map;
}

void BM_BuildCostmap(benchmark::State& state) {
  const mapping::MapImage map = ObstacleField(kSize, 1);
  for (auto _ : state) benchmark::DoNotOptimize(BuildCostmap(map, {}).ok());
  state.SetItemsProcessed(state.iterations() * kSize * kSize);  // cells per second
}
BENCHMARK(BM_BuildCostmap)->Unit(benchmark::kMillisecond);

// A* from one corner to the opposite one; the argument is the cost weight (0: shortest path).
void BM_AStarAcrossTheMap(benchmark::State& state) {
  const Result<Costmap> costmap = BuildCostmap(ObstacleField(kSize, 1), {});
  AStarOptions options;
  options.cost_weight = static_cast<double>(state.range(0));
  const Eigen::Vector2i start(20, 20), goal(kSize - 20, kSize - 20);
  double length = 0.0;
  for (auto _ : state) {
    const auto path = PlanGridPath(*costmap, start, goal, options);
    if (!path) state.SkipWithError("no path");
    length = path ? path->length_meters : 0.0;
  }
  state.counters["length_m"] = length;
}
BENCHMARK(BM_AStarAcrossTheMap)->Arg(0)->Arg(3)->Unit(benchmark::kMillisecond);

// One 320 × 240 depth frame (a wall 3 m ahead, floor below) to a virtual scan: frames per second.
void BM_DepthToScan(benchmark::State& state) {
  MountedCamera camera;
  camera.intrinsics = PinholeCamera::FromFov(320, 240, DegToRad(60.0));
  camera.robot_from_camera = RobotFromOpticalCamera(0.0, 0.0, 0.5, 0.0, DegToRad(10.0));
  const DepthToScanConverter converter(camera, DepthToScanOptions{});
  cv::Mat depth(240, 320, CV_32FC1, cv::Scalar(3.0f));
  for (auto _ : state) benchmark::DoNotOptimize(converter.Convert(depth, 0.0).ranges.data());
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DepthToScan);

}  // namespace
}  // namespace semchain::planning

BENCHMARK_MAIN();
