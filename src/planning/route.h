#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/status.h"
#include "planning/astar.h"
#include "planning/costmap.h"

// Multi-goal routes (seed 004 §3.2, Fig. 11): from the start S to P1, then from P1 to P2, …,
// each leg planned by A* from where the previous one ended.
namespace semchain::planning {

struct Route {
  std::vector<Eigen::Vector2d> points;  // cell centres, map coordinates, start to last goal
  double cost = 0.0;                    // sum of the legs' A* costs
  double length_meters = 0.0;           // length of the polyline 'points'
  std::vector<std::size_t> leg_ends;    // index in 'points' where each leg ends
};

// Plans S → P1 → … through 'waypoints' (S first, at least one goal after it). Errors, one line
// naming the point: outside the map, inside an obstacle, a keep-out zone, within the robot
// radius of an obstacle, in unknown space; a goal that cannot be reached from the point before.
Result<Route> PlanRoute(const Costmap& costmap, const std::vector<Eigen::Vector2d>& waypoints,
                        const AStarOptions& options = {});

}  // namespace semchain::planning
