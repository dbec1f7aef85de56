#include "testing/truth_maps.h"

#include <cmath>

#include "semantic/semantic_chain.h"
#include "sensors/detection.h"
#include "sim/prism_silhouette.h"
#include "sim/scene.h"

namespace semchain::e2e {

TruthMaps MapsFromTruth(const sim::World& world) {
  constexpr double kResolution = 0.05, kMargin = 0.25;
  Eigen::Vector2d low(1e300, 1e300), high(-1e300, -1e300);
  for (const auto& wall : world.walls) {
    for (const Eigen::Vector2d& p : wall) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
  }
  TruthMaps maps;
  mapping::MapImage& map = maps.occupancy;
  map.resolution = kResolution;
  map.origin << low.x() - kMargin, low.y() - kMargin, 0.0;
  map.width = static_cast<int>(std::ceil((high.x() - low.x() + 2 * kMargin) / kResolution));
  map.height = static_cast<int>(std::ceil((high.y() - low.y() + 2 * kMargin) / kResolution));
  const sim::Scene scene(world);
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      const Eigen::Vector2d p =
          map.origin.head<2>() + kResolution * Eigen::Vector2d(x + 0.5, y + 0.5);
      const bool inside = (p.array() >= low.array()).all() && (p.array() <= high.array()).all();
      map.cells.push_back(scene.IsOccupied(p, 0.5 * kResolution) ? 100 : inside ? 0 : -1);
    }
  }
  semantic::SemanticMap& objects = maps.semantic;
  objects.classes = world.classes.empty() ? DefaultClassNames() : world.classes;
  for (const sim::Solid& solid : world.objects) {
    objects.objects.push_back({static_cast<int>(objects.objects.size()), solid.class_name,
                               solid.footprint.center, sim::FootprintOutline(solid.footprint), 10,
                               0.9});
  }
  semantic::BuildChainsAndNeighbours(map, semantic::ChainOptions(), {}, &objects);
  return maps;
}

}  // namespace semchain::e2e
