#include "mapping/distance_field.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "core/check.h"

namespace semchain::mapping {

CellState ClassifyMapCell(const MapImage& map, int x, int y) {
  const int value = map.At(x, y);
  if (value < 0) return CellState::kUnknown;
  if (value >= map.occupied_thresh * 100.0) return CellState::kOccupied;
  if (value <= map.free_thresh * 100.0) return CellState::kFree;
  return CellState::kUnknown;
}

cv::Mat MapCellMask(const MapImage& map, CellState state) {
  cv::Mat mask(map.height, map.width, CV_8UC1, cv::Scalar(0));
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      if (ClassifyMapCell(map, x, y) == state) mask.at<std::uint8_t>(y, x) = 255;
    }
  }
  return mask;
}

DistanceField::DistanceField(const MapImage& map, double max_distance_meters)
    : width_(map.width),
      height_(map.height),
      resolution_(map.resolution),
      origin_(map.origin.x(), map.origin.y()),
      max_distance_(max_distance_meters) {
  SEMCHAIN_CHECK(width_ > 0 && height_ > 0 && resolution_ > 0.0 && max_distance_ > 0.0);
  // distanceTransform measures the distance to the nearest zero pixel: occupied cells are 0.
  cv::Mat_<unsigned char> source(height_, width_, static_cast<unsigned char>(1));
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      if (ClassifyMapCell(map, x, y) == CellState::kOccupied) source(y, x) = 0;
    }
  }
  cv::Mat distances;
  cv::distanceTransform(source, distances, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  distances_.resize(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_));
  const float cap = static_cast<float>(max_distance_);
  const float scale = static_cast<float>(resolution_);
  for (int y = 0; y < height_; ++y) {
    const float* row = distances.ptr<float>(y);
    for (int x = 0; x < width_; ++x) {
      distances_[static_cast<std::size_t>(y * width_ + x)] = std::min(cap, row[x] * scale);
    }
  }
}

}  // namespace semchain::mapping
