#include "localization/localization_map.h"

#include <cmath>
#include <limits>
#include <random>

#include "core/angles.h"
#include "core/check.h"

namespace semchain::localization {

LocalizationMap::LocalizationMap(const mapping::MapImage& map, double likelihood_max_dist)
    : field_(map, likelihood_max_dist), quantized_(field_) {
  states_.resize(static_cast<std::size_t>(map.width) * static_cast<std::size_t>(map.height));
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      const mapping::CellState state = mapping::ClassifyMapCell(map, x, y);
      states_[static_cast<std::size_t>(y * map.width + x)] = state;
      if (state == mapping::CellState::kFree) free_cells_.emplace_back(x, y);
    }
  }
}

Pose2 LocalizationMap::RandomFreePose(Rng& rng) const {
  SEMCHAIN_CHECK(!free_cells_.empty());
  std::uniform_int_distribution<std::size_t> pick(0, free_cells_.size() - 1);
  const Eigen::Vector2i& cell = free_cells_[pick(rng)];
  const double x = field_.origin().x() + (cell.x() + 0.5) * resolution();
  const double y = field_.origin().y() + (cell.y() + 0.5) * resolution();
  return Pose2(x, y, std::uniform_real_distribution<double>(-kPi, kPi)(rng));
}

double LocalizationMap::CalcRange(const Eigen::Vector2d& origin, double angle,
                                  double max_range) const {
  // Amanatides & Woo traversal in cell units: visit cells in the order the ray enters them.
  const double inverse = 1.0 / resolution();
  const Eigen::Vector2d start = (origin - field_.origin()) * inverse;
  const Eigen::Vector2d direction(std::cos(angle), std::sin(angle));
  Eigen::Vector2i cell(static_cast<int>(std::floor(start.x())),
                       static_cast<int>(std::floor(start.y())));
  const int step_x = direction.x() >= 0.0 ? 1 : -1;
  const int step_y = direction.y() >= 0.0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  const double delta_x = direction.x() != 0.0 ? std::abs(1.0 / direction.x()) : inf;
  const double delta_y = direction.y() != 0.0 ? std::abs(1.0 / direction.y()) : inf;
  double next_x = direction.x() != 0.0
                      ? ((step_x > 0 ? cell.x() + 1 - start.x() : start.x() - cell.x()) * delta_x)
                      : inf;
  double next_y = direction.y() != 0.0
                      ? ((step_y > 0 ? cell.y() + 1 - start.y() : start.y() - cell.y()) * delta_y)
                      : inf;
  const double limit = max_range * inverse;
  double travelled = 0.0;
  while (travelled < limit) {
    if (State(cell) != mapping::CellState::kFree) return travelled * resolution();
    if (next_x < next_y) {
      travelled = next_x;
      next_x += delta_x;
      cell.x() += step_x;
    } else {
      travelled = next_y;
      next_y += delta_y;
      cell.y() += step_y;
    }
  }
  return max_range;
}

}  // namespace semchain::localization
