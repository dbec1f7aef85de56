// One semantic pre-localization query (seed 001 retrieval + two-circle intersection, every pair
// of the objects in view) on a map of 1000 objects: the cost of relocalizing from a frame.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "core/rng.h"
#include "localization/prelocalization.h"

namespace semchain::localization {
namespace {

constexpr int kObjects = 1000;
constexpr double kSide = 100.0;  // metres: a large building's floor

semantic::SemanticObject Box(int id, const std::string& class_name, double x, double y) {
  semantic::SemanticObject object;
  object.id = id;
  object.class_name = class_name;
  object.center = {x, y};
  object.footprint = {
      {x + 0.2, y + 0.2}, {x - 0.2, y + 0.2}, {x - 0.2, y - 0.2}, {x + 0.2, y - 0.2}};
  return object;
}

void BM_PreLocalize1000Objects(benchmark::State& state) {
  const std::vector<std::string> classes = {"door", "cabinet", "bucket", "chair", "stool"};
  Rng rng = MakeRng(7, 0);
  std::uniform_real_distribution<double> where(1.0, kSide - 1.0);
  semantic::SemanticMap map;
  for (int i = 0; i < kObjects; ++i) {
    map.objects.push_back(
        Box(i, classes[static_cast<std::size_t>(i) % classes.size()], where(rng), where(rng)));
  }
  mapping::MapImage occupancy;
  occupancy.resolution = 0.1;
  occupancy.width = occupancy.height = static_cast<int>(kSide / occupancy.resolution);
  occupancy.cells.assign(static_cast<std::size_t>(occupancy.width * occupancy.height), 0);
  const PreLocalizer localizer(map, occupancy, PreLocalizationOptions());
  // What a robot next to object 0 sees of its three nearest objects.
  const Pose2 robot(map.objects[0].center.x() - 1.5, map.objects[0].center.y(), 0.0);
  std::vector<std::pair<double, int>> nearest;
  for (const semantic::SemanticObject& o : map.objects) {
    nearest.emplace_back((o.center - robot.translation()).norm(), o.id);
  }
  std::sort(nearest.begin(), nearest.end());
  std::vector<ObservedObject> observed;
  for (int k = 0; k < 3; ++k) {
    const semantic::SemanticObject& o = map.objects[static_cast<std::size_t>(nearest[k].second)];
    const Eigen::Vector2d centre = robot.Inverse() * o.center;
    ObservedObject seen;
    seen.class_name = o.class_name;
    seen.surface = centre - 0.2 * centre.normalized();
    seen.range = seen.surface.norm();
    seen.bearing = std::atan2(seen.surface.y(), seen.surface.x());
    observed.push_back(seen);
  }
  std::size_t hypotheses = 0;
  for (auto _ : state) {
    const auto result = localizer.Localize(observed);
    hypotheses = result.size();
    benchmark::DoNotOptimize(result.data());
  }
  state.counters["hypotheses"] = static_cast<double>(hypotheses);
}
BENCHMARK(BM_PreLocalize1000Objects)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace semchain::localization

BENCHMARK_MAIN();
