#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "mapping/map_io.h"

// Test helper: small map_server maps drawn as text, and seeded random maps.
namespace semchain::planning::testing {

// A map from rows of text, the first row at the top (largest y) as in the map image:
// '#' occupied, '.' free, '?' unknown. Resolution 'resolution', origin (0, 0).
inline mapping::MapImage MapFromText(const std::vector<std::string>& rows,
                                     double resolution = 0.1) {
  mapping::MapImage map;
  map.height = static_cast<int>(rows.size());
  map.width = static_cast<int>(rows.front().size());
  map.resolution = resolution;
  map.cells.resize(static_cast<std::size_t>(map.width * map.height));
  for (int row = 0; row < map.height; ++row) {
    for (int x = 0; x < map.width; ++x) {
      const char c = rows[static_cast<std::size_t>(row)][static_cast<std::size_t>(x)];
      const std::int8_t value = c == '#' ? 100 : (c == '?' ? -1 : 0);
      map.cells[static_cast<std::size_t>((map.height - 1 - row) * map.width + x)] = value;
    }
  }
  return map;
}

// A free 'width' × 'height' map with each cell occupied with probability 'density'.
inline mapping::MapImage RandomMap(int width, int height, double density, std::uint64_t seed,
                                   double resolution = 0.05) {
  mapping::MapImage map;
  map.width = width;
  map.height = height;
  map.resolution = resolution;
  map.cells.assign(static_cast<std::size_t>(width * height), 0);
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution occupied(density);
  for (std::int8_t& cell : map.cells) cell = occupied(rng) ? 100 : 0;
  return map;
}

}  // namespace semchain::planning::testing
