#pragma once

#include <Eigen/Core>
#include <cmath>

namespace semchain::semantic {

// The cells of a map: cell (x, y) covers [origin + (x, y) r, origin + (x + 1, y + 1) r), row y = 0
// at the bottom as in map_server maps; images of the layers use row = y.
struct GridGeometry {
  int width = 0;
  int height = 0;
  double resolution = 0.05;
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();

  // Seed 000 eq. 5 (the cell that contains the point, see core/transforms.h).
  Eigen::Vector2i CellOf(const Eigen::Vector2d& world) const {
    return {static_cast<int>(std::floor((world.x() - origin.x()) / resolution)),
            static_cast<int>(std::floor((world.y() - origin.y()) / resolution))};
  }
  Eigen::Vector2d CenterOf(const Eigen::Vector2i& cell) const {
    return origin + (cell.cast<double>().array() + 0.5).matrix() * resolution;
  }
  bool Contains(const Eigen::Vector2i& cell) const {
    return cell.x() >= 0 && cell.y() >= 0 && cell.x() < width && cell.y() < height;
  }
};

}  // namespace semchain::semantic
