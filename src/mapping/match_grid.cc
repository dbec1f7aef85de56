#include "mapping/match_grid.h"

#include <cmath>
#include <limits>

#include "core/check.h"
#include "mapping/distance_field.h"

namespace semchain::mapping {

bool MatchGridOptions::Validate(std::string* error) const {
  if (!(sigma_meters > 0.0)) {
    *error = "sigma_meters must be positive";
    return false;
  }
  if (!(unknown_value >= 0.0 && unknown_value <= 1.0)) {
    *error = "unknown_value must be in [0, 1]";
    return false;
  }
  return true;
}

MatchGrid MakeMatchGrid(const MapImage& map, const MatchGridOptions& options) {
  std::string error;
  SEMCHAIN_CHECK(options.Validate(&error));
  // Beyond 4 σ, M < 3.4e-4: cap the distances there.
  const DistanceField field(map, 4.0 * options.sigma_meters);
  MatchGrid grid;
  grid.width = map.width;
  grid.height = map.height;
  grid.resolution = map.resolution;
  grid.origin = Eigen::Vector2d(map.origin.x(), map.origin.y());
  grid.values.resize(static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height));
  const double factor = -0.5 / (options.sigma_meters * options.sigma_meters);
  grid.outside = static_cast<float>(options.unknown_value);
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      const double d = field.DistanceAtCell({x, y});
      float m = d >= field.max_distance() ? 0.0f : static_cast<float>(std::exp(factor * d * d));
      if (map.At(x, y) < 0) m = std::max(m, grid.outside);
      grid.values[static_cast<std::size_t>(y * grid.width + x)] = m;
    }
  }
  return grid;
}

double CellScore(const MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                 const Pose2& pose) {
  return CellScoreIfAtLeast(grid, points, pose, -std::numeric_limits<double>::infinity());
}

double CellScoreIfAtLeast(const MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                          const Pose2& pose, double at_least) {
  if (points.empty()) return 0.0;
  const Eigen::Isometry2d transform = pose.ToIsometry();
  const double count = static_cast<double>(points.size());
  // A hair below the bound, so that rounding never drops a pose whose mean reaches it.
  const double needed = at_least * count - 1e-9 * count;
  double sum = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Eigen::Vector2i cell = grid.CellOf(transform * points[k]);
    sum += grid.At(cell.x(), cell.y());
    if (sum + static_cast<double>(points.size() - k - 1) < needed) return -1.0;
  }
  return sum / count;
}

}  // namespace semchain::mapping
