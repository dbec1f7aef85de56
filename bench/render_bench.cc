// Throughput of the simulator's camera: rendered RGB-D frames per second and detections per
// second in a furnished room (sim/furnished_room.h), at 320 × 240 and 640 × 480.
#include <benchmark/benchmark.h>

#include <vector>

#include "core/rng.h"
#include "sim/detection_model.h"
#include "sim/furnished_room.h"
#include "sim/rgbd_renderer.h"

namespace semchain::sim {
namespace {

// Viewpoints spread over the room, looking at walls, objects and the column.
const std::vector<Pose2>& Poses() {
  static const std::vector<Pose2> kPoses = {{2.0, 3.0, 0.0},  {2.0, 3.0, 0.5}, {2.0, 3.0, -0.6},
                                            {4.0, 4.0, 0.3},  {6.0, 2.0, 2.5}, {3.0, 1.5, 1.2},
                                            {5.0, 3.0, -1.2}, {1.5, 4.5, -0.4}};
  return kPoses;
}

World RoomWithCamera(int width, int height) {
  World world = FurnishedRoomWorld();
  world.robot.camera.width = width;
  world.robot.camera.height_px = height;
  world.robot.camera.depth_noise_std = 0.005;
  return world;
}

void BM_RenderRgbd(benchmark::State& state) {
  const World world =
      RoomWithCamera(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const Scene scene(world);
  const MountedCamera camera = MakeMountedCamera(world.robot.camera);
  std::uint64_t frame = 0;
  for (auto _ : state) {
    const Pose2& pose = Poses()[frame % Poses().size()];
    RgbdImage image = RenderRgbd(scene, camera, pose, MakeRenderOptions(world.robot.camera, frame));
    benchmark::DoNotOptimize(image.rgb.data);
    ++frame;
  }
  state.counters["frames_per_s"] =
      benchmark::Counter(static_cast<double>(frame), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RenderRgbd)->Args({320, 240})->Args({640, 480})->Unit(benchmark::kMillisecond);

// Detection alone, on frames rendered beforehand.
void BM_DetectObjects(benchmark::State& state) {
  const World world =
      RoomWithCamera(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const Scene scene(world);
  const MountedCamera camera = MakeMountedCamera(world.robot.camera);
  std::vector<RgbdImage> images;
  for (const Pose2& pose : Poses()) images.push_back(RenderRgbd(scene, camera, pose));
  Rng rng = MakeRng(1);
  std::size_t frame = 0, detections = 0;
  for (auto _ : state) {
    const std::size_t i = frame++ % images.size();
    detections += DetectObjects(scene, camera, Poses()[i], images[i], rng).size();
  }
  state.counters["frames_per_s"] =
      benchmark::Counter(static_cast<double>(frame), benchmark::Counter::kIsRate);
  state.counters["detections_per_s"] =
      benchmark::Counter(static_cast<double>(detections), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_DetectObjects)->Args({320, 240})->Args({640, 480})->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace semchain::sim

BENCHMARK_MAIN();
