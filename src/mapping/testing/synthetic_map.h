#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "mapping/map_io.h"
#include "mapping/testing/synthetic_world.h"

// Test helper: a map_server map of a segment world, every cell a segment passes through
// occupied (100), every other cell free (0).
namespace semchain::mapping::testing {

inline MapImage RasterizeWorld(const std::vector<Segment>& world, const Eigen::Vector2d& min,
                               const Eigen::Vector2d& max, double resolution = 0.05) {
  MapImage map;
  map.resolution = resolution;
  map.origin = Eigen::Vector3d(min.x(), min.y(), 0.0);
  map.width = static_cast<int>(std::ceil((max.x() - min.x()) / resolution));
  map.height = static_cast<int>(std::ceil((max.y() - min.y()) / resolution));
  map.cells.assign(static_cast<std::size_t>(map.width * map.height), 0);
  for (const Segment& s : world) {
    const int steps = static_cast<int>(std::ceil((s.b - s.a).norm() / (0.25 * resolution))) + 1;
    for (int i = 0; i <= steps; ++i) {
      const Eigen::Vector2d p = s.a + (s.b - s.a) * (static_cast<double>(i) / steps);
      const int x = static_cast<int>(std::floor((p.x() - min.x()) / resolution));
      const int y = static_cast<int>(std::floor((p.y() - min.y()) / resolution));
      if (x >= 0 && y >= 0 && x < map.width && y < map.height) {
        map.cells[static_cast<std::size_t>(y * map.width + x)] = 100;
      }
    }
  }
  return map;
}

// RoomWorld() on a map with a 1 m margin, shifted by half a cell so that its walls (on
// multiples of 5 cm) run through cell centres and the map has no half-cell bias.
inline MapImage RoomMap(double resolution = 0.05) {
  const Eigen::Vector2d shift(0.5 * resolution, 0.5 * resolution);
  return RasterizeWorld(RoomWorld(), Eigen::Vector2d(-6.0, -5.0) - shift,
                        Eigen::Vector2d(6.0, 5.0) - shift, resolution);
}

}  // namespace semchain::mapping::testing
