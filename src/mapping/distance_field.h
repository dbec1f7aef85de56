#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "mapping/map_io.h"

// The distance from every cell of a map_server map to the nearest occupied cell, computed once
// per map (nav2 amcl's occ_dist, Probabilistic Robotics §6.4) so that a likelihood-field lookup
// is one array access. Exact Euclidean distances between cell centres (cv::distanceTransform
// with the precise mask), capped at a maximum distance.
namespace semchain::mapping {

enum class CellState : signed char { kFree = -1, kUnknown = 0, kOccupied = 1 };

// How map_server thresholds a cell value (0..100, -1 unknown): occupied at or above
// occupied_thresh, free at or below free_thresh, unknown in between.
CellState ClassifyMapCell(const MapImage& map, int x, int y);

// CV_8UC1 of the map's size, row = cell y (row 0 at the bottom): 255 where ClassifyMapCell gives
// 'state', 0 elsewhere.
cv::Mat MapCellMask(const MapImage& map, CellState state);

class DistanceField {
 public:
  // Distances for 'map' (its yaw must be 0, as nav2 requires), capped at 'max_distance_meters'
  // (nav2's laser_likelihood_max_dist).
  DistanceField(const MapImage& map, double max_distance_meters);

  int width() const { return width_; }
  int height() const { return height_; }
  double resolution() const { return resolution_; }
  const Eigen::Vector2d& origin() const { return origin_; }
  double max_distance() const { return max_distance_; }

  // The cell containing 'world' (may lie outside the map).
  Eigen::Vector2i CellOf(const Eigen::Vector2d& world) const {
    return {static_cast<int>(std::floor((world.x() - origin_.x()) / resolution_)),
            static_cast<int>(std::floor((world.y() - origin_.y()) / resolution_))};
  }
  bool Contains(const Eigen::Vector2i& cell) const {
    return cell.x() >= 0 && cell.y() >= 0 && cell.x() < width_ && cell.y() < height_;
  }
  // Metres to the nearest occupied cell centre; max_distance() outside the map.
  double DistanceAtCell(const Eigen::Vector2i& cell) const {
    return Contains(cell) ? distances_[static_cast<std::size_t>(cell.y() * width_ + cell.x())]
                          : max_distance_;
  }
  double DistanceAt(const Eigen::Vector2d& world) const { return DistanceAtCell(CellOf(world)); }

 private:
  int width_;
  int height_;
  double resolution_;
  Eigen::Vector2d origin_;
  double max_distance_;
  std::vector<float> distances_;  // row-major, row 0 at the bottom (y = origin.y)
};

}  // namespace semchain::mapping
