#include "planning/costmap.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace semchain::planning {
namespace {

// 255 where 'map' has an obstacle, else 0 (row y = map row y).
cv::Mat ObstacleMask(const mapping::MapImage& map) {
  cv::Mat mask(map.height, map.width, CV_8UC1, cv::Scalar(0));
  const double occupied = 100.0 * map.occupied_thresh;
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      if (map.At(x, y) >= occupied) mask.at<std::uint8_t>(y, x) = 255;
    }
  }
  return mask;
}

// Clears the 8-connected components of 'mask' smaller than 'min_cells'; returns the number of
// cells cleared.
int RemoveSmallComponents(int min_cells, cv::Mat* mask) {
  if (min_cells <= 1) return 0;
  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(*mask, labels, stats, centroids, 8, CV_32S);
  std::vector<bool> small(static_cast<std::size_t>(count), false);
  for (int label = 1; label < count; ++label) {  // label 0 is the background
    small[static_cast<std::size_t>(label)] = stats.at<int>(label, cv::CC_STAT_AREA) < min_cells;
  }
  int removed = 0;
  for (int y = 0; y < mask->rows; ++y) {
    for (int x = 0; x < mask->cols; ++x) {
      if (small[static_cast<std::size_t>(labels.at<int>(y, x))] && mask->at<std::uint8_t>(y, x)) {
        mask->at<std::uint8_t>(y, x) = 0;
        ++removed;
      }
    }
  }
  return removed;
}

// 255 inside the keep-out polygons (OpenCV's scan-line fill; cells the boundary touches count).
cv::Mat KeepoutMask(const Costmap& costmap, const std::vector<Polygon>& zones) {
  cv::Mat mask(costmap.height, costmap.width, CV_8UC1, cv::Scalar(0));
  constexpr int kShift = 8;  // sub-cell precision of the vertices, bits
  for (const Polygon& zone : zones) {
    std::vector<cv::Point> vertices;
    for (const Eigen::Vector2d& p : zone) {
      // Cell centres are at integer pixel coordinates.
      const Eigen::Vector2d pixel = (p - costmap.origin) / costmap.resolution;
      vertices.emplace_back(static_cast<int>(std::lround((pixel.x() - 0.5) * (1 << kShift))),
                            static_cast<int>(std::lround((pixel.y() - 0.5) * (1 << kShift))));
    }
    cv::fillPoly(mask, std::vector<std::vector<cv::Point>>{vertices}, cv::Scalar(255), cv::LINE_8,
                 kShift);
  }
  return mask;
}

}  // namespace

bool CostmapOptions::Validate(std::string* error) const {
  if (!(robot_radius_meters >= 0.0)) {
    *error = "robot radius must be >= 0";
    return false;
  }
  if (!(inflation_radius_meters >= robot_radius_meters)) {
    *error = "inflation radius must be >= the robot radius";
    return false;
  }
  if (!(cost_scaling_factor > 0.0)) {
    *error = "cost scaling factor must be positive";
    return false;
  }
  return true;
}

Eigen::Vector2i Costmap::CellOf(const Eigen::Vector2d& world) const {
  return {static_cast<int>(std::floor((world.x() - origin.x()) / resolution)),
          static_cast<int>(std::floor((world.y() - origin.y()) / resolution))};
}

Eigen::Vector2d Costmap::CellCenter(const Eigen::Vector2i& cell) const {
  return origin + (cell.cast<double>() + Eigen::Vector2d(0.5, 0.5)) * resolution;
}

std::uint8_t InflationCost(double distance_meters, const CostmapOptions& options) {
  if (distance_meters <= 0.0) return kLethalCost;
  if (distance_meters <= options.robot_radius_meters) return kInscribedCost;
  if (distance_meters > options.inflation_radius_meters) return kFreeCost;
  const double factor =
      std::exp(-options.cost_scaling_factor * (distance_meters - options.robot_radius_meters));
  return static_cast<std::uint8_t>((kInscribedCost - 1) * factor);
}

Result<Costmap> BuildCostmap(const mapping::MapImage& map, const std::vector<Polygon>& keepout,
                             const CostmapOptions& options) {
  std::string error;
  if (!options.Validate(&error)) return Status::Error("invalid costmap options: " + error);
  if (map.width <= 0 || map.height <= 0) return Status::Error("the map is empty");
  if (std::abs(map.origin.z()) > 1e-9) {
    return Status::Error("maps with a rotated origin (yaw != 0) are not supported");
  }
  Costmap costmap;
  costmap.width = map.width;
  costmap.height = map.height;
  costmap.resolution = map.resolution;
  costmap.origin = map.origin.head<2>();
  cv::Mat obstacles = ObstacleMask(map);
  costmap.removed_noise_cells = RemoveSmallComponents(options.min_obstacle_cells, &obstacles);
  costmap.keepout = KeepoutMask(costmap, keepout);

  // Distance of every cell centre to the nearest inflation source, exact Euclidean, in cells.
  cv::Mat sources = obstacles.clone();
  if (options.inflate_keepout) sources |= costmap.keepout;
  cv::Mat distance;
  cv::distanceTransform(~sources, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);

  costmap.cost = cv::Mat(map.height, map.width, CV_8UC1);
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      std::uint8_t cost = InflationCost(distance.at<float>(y, x) * map.resolution, options);
      if (costmap.keepout.at<std::uint8_t>(y, x) != 0) cost = kLethalCost;
      if (map.At(x, y) < 0 && cost < kInscribedCost && options.unknown == UnknownPolicy::kLethal) {
        cost = kUnknownCost;
      }
      costmap.cost.at<std::uint8_t>(y, x) = cost;
    }
  }
  return costmap;
}

}  // namespace semchain::planning
