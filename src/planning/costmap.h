#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/status.h"
#include "mapping/map_io.h"
#include "planning/keepout.h"

// An inflated costmap for planning (seed 004 §3.2, DESIGN.md §3.9), built the way nav2's static
// and inflation layers build theirs: occupied map cells are lethal, cells whose centre lies
// within the robot's radius of one are "inscribed" (the robot would touch it), and the cost
// decays exponentially out to the inflation radius. Keep-out zones are lethal too, and small
// isolated groups of occupied cells (people walking through while mapping) are removed first.
namespace semchain::planning {

// Cell costs, as in nav2_costmap_2d.
inline constexpr std::uint8_t kFreeCost = 0;
inline constexpr std::uint8_t kInscribedCost = 253;
inline constexpr std::uint8_t kLethalCost = 254;
inline constexpr std::uint8_t kUnknownCost = 255;  // "no information"

// What an unknown map cell is for the planner.
enum class UnknownPolicy {
  kLethal,  // not traversable (the robot stays where the map says it can), not inflated
  kFree,    // traversable at no cost
};

struct CostmapOptions {
  // The robot's circumscribed radius: a cell closer than this to an obstacle is a collision.
  double robot_radius_meters = 0.2;
  // Costs decay out to this distance from obstacles (nav2 default 0.55 m).
  double inflation_radius_meters = 0.55;
  // The decay rate of the inflation cost per metre beyond the robot radius (nav2's
  // cost_scaling_factor; its example configurations use 3.0).
  double cost_scaling_factor = 3.0;
  UnknownPolicy unknown = UnknownPolicy::kLethal;
  // Occupied 8-connected components with fewer cells than this are noise and removed before
  // inflation; 2 removes single stray cells only, 0 or 1 keeps everything.
  int min_obstacle_cells = 2;
  // Keep-out zones are inflated like obstacles, so the robot's body stays out of them too
  // (seed 004: "set a boundary inflation range"); false keeps only their own cells lethal.
  bool inflate_keepout = true;

  bool Validate(std::string* error) const;
};

// Costs of a map_server map's cells: 'cost' is CV_8UC1 with row y = map row y (row 0 at
// origin.y, the bottom of the map image).
struct Costmap {
  int width = 0;
  int height = 0;
  double resolution = 0.05;
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  cv::Mat cost;     // CV_8UC1, the values above
  cv::Mat keepout;  // CV_8UC1, 255 inside a keep-out zone
  int removed_noise_cells = 0;

  bool Contains(const Eigen::Vector2i& cell) const {
    return cell.x() >= 0 && cell.y() >= 0 && cell.x() < width && cell.y() < height;
  }
  std::uint8_t At(const Eigen::Vector2i& cell) const {
    return cost.at<std::uint8_t>(cell.y(), cell.x());
  }
  bool InKeepout(const Eigen::Vector2i& cell) const {
    return keepout.at<std::uint8_t>(cell.y(), cell.x()) != 0;
  }
  // The robot's centre may be in a cell whose cost is below kInscribedCost.
  bool Traversable(const Eigen::Vector2i& cell) const {
    return Contains(cell) && At(cell) < kInscribedCost;
  }
  Eigen::Vector2i CellOf(const Eigen::Vector2d& world) const;
  Eigen::Vector2d CellCenter(const Eigen::Vector2i& cell) const;
};

// Builds the costmap of 'map' with 'keepout' zones (map coordinates). Map cells at or above
// occupied_thresh are obstacles, unknown cells (-1) follow options.unknown, the rest is free.
// Errors: a rotated map origin (yaw != 0), an empty map.
Result<Costmap> BuildCostmap(const mapping::MapImage& map, const std::vector<Polygon>& keepout,
                             const CostmapOptions& options = {});

// The inflation cost of a cell 'distance_meters' from the nearest obstacle (nav2's formula):
// lethal at 0, inscribed within the robot radius, 252·exp(−k (d − r)) up to the inflation
// radius (252 = inscribed − 1, so the decay never reaches a collision value), 0 beyond.
std::uint8_t InflationCost(double distance_meters, const CostmapOptions& options);

}  // namespace semchain::planning
