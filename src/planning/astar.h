#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "planning/costmap.h"

// A* on the 8-connected grid of a costmap (seed 004 §3.2).
//
// A step from a cell to a neighbour costs its length (resolution, or resolution·√2 on a
// diagonal) times 1 + cost_weight · c / 252, where c is the neighbour's costmap value: free
// space costs the distance travelled, inflated cells near obstacles cost up to 1 + cost_weight
// times as much, so paths keep away from obstacles when the detour is cheap. Cells of cost
// kInscribedCost and above cannot be entered. The heuristic is the octile distance times the
// resolution: the cheapest possible cost to the goal (every step costs at least its length),
// so it is admissible and consistent and A* returns a minimum-cost path.
namespace semchain::planning {

struct AStarOptions {
  // Weight of the inflation cost in the step cost (0: shortest path in the free space).
  double cost_weight = 3.0;
  // A diagonal step needs both cells beside it to be traversable, so a path never squeezes
  // between two obstacle cells touching at a corner.
  bool allow_corner_cutting = false;

  bool Validate(std::string* error) const;
};

struct GridPath {
  std::vector<Eigen::Vector2i> cells;  // start to goal, each a neighbour of the previous one
  double cost = 0.0;                   // sum of the step costs
  double length_meters = 0.0;          // sum of the step lengths
};

// Cost of the step from 'from' to its neighbour 'to' (see above); +inf if 'to' cannot be
// entered or the step cuts a corner that options forbid.
double StepCost(const Costmap& costmap, const Eigen::Vector2i& from, const Eigen::Vector2i& to,
                const AStarOptions& options);

// A minimum-cost path from 'start' to 'goal' (both traversable cells), or nothing when the goal
// cannot be reached.
std::optional<GridPath> PlanGridPath(const Costmap& costmap, const Eigen::Vector2i& start,
                                     const Eigen::Vector2i& goal, const AStarOptions& options = {});

}  // namespace semchain::planning
