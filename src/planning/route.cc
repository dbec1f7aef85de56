#include "planning/route.h"

#include <cstdio>

namespace semchain::planning {
namespace {

std::string Describe(const std::vector<Eigen::Vector2d>& waypoints, std::size_t i) {
  char text[96];
  if (i == 0) {
    std::snprintf(text, sizeof(text), "start (%.3f, %.3f)", waypoints[i].x(), waypoints[i].y());
  } else {
    std::snprintf(text, sizeof(text), "goal %zu (%.3f, %.3f)", i, waypoints[i].x(),
                  waypoints[i].y());
  }
  return text;
}

// Why the robot's centre cannot be at 'point', or OK.
Status CheckPoint(const Costmap& costmap, const std::vector<Eigen::Vector2d>& waypoints,
                  std::size_t i) {
  const Eigen::Vector2i cell = costmap.CellOf(waypoints[i]);
  const std::string name = Describe(waypoints, i);
  if (!costmap.Contains(cell)) {
    char extent[128];
    const Eigen::Vector2d max =
        costmap.origin + Eigen::Vector2d(costmap.width, costmap.height) * costmap.resolution;
    std::snprintf(extent, sizeof(extent), " (x in [%.3f, %.3f], y in [%.3f, %.3f])",
                  costmap.origin.x(), max.x(), costmap.origin.y(), max.y());
    return Status::Error(name + " is outside the map" + extent);
  }
  if (costmap.InKeepout(cell)) return Status::Error(name + " is inside a keep-out zone");
  switch (costmap.At(cell)) {
    case kLethalCost:
      return Status::Error(name + " is inside an obstacle");
    case kInscribedCost:
      return Status::Error(name +
                           " is closer to an obstacle or keep-out zone than the robot "
                           "radius");
    case kUnknownCost:
      return Status::Error(name + " is in unknown space");
    default:
      return Status::Ok();
  }
}

}  // namespace

Result<Route> PlanRoute(const Costmap& costmap, const std::vector<Eigen::Vector2d>& waypoints,
                        const AStarOptions& options) {
  if (waypoints.size() < 2) return Status::Error("a route needs a start and at least one goal");
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    SEMCHAIN_RETURN_IF_ERROR(CheckPoint(costmap, waypoints, i));
  }
  Route route;
  for (std::size_t i = 1; i < waypoints.size(); ++i) {
    const std::optional<GridPath> leg = PlanGridPath(costmap, costmap.CellOf(waypoints[i - 1]),
                                                     costmap.CellOf(waypoints[i]), options);
    if (!leg) {
      return Status::Error("no path from " + Describe(waypoints, i - 1) + " to " +
                           Describe(waypoints, i) + ": unreachable");
    }
    // Each leg starts in the cell where the previous one ended; keep that cell once.
    for (std::size_t k = route.points.empty() ? 0 : 1; k < leg->cells.size(); ++k) {
      route.points.push_back(costmap.CellCenter(leg->cells[k]));
    }
    route.cost += leg->cost;
    route.length_meters += leg->length_meters;
    route.leg_ends.push_back(route.points.size() - 1);
  }
  return route;
}

}  // namespace semchain::planning
