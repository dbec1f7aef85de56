#include "planning/astar.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <utility>

#include "core/check.h"

namespace semchain::planning {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kSqrt2 = 1.4142135623730951;
constexpr int kDx[8] = {1, -1, 0, 0, 1, 1, -1, -1};
constexpr int kDy[8] = {0, 0, 1, -1, 1, -1, 1, -1};

// Octile distance between two cells, metres: the length of the shortest 8-connected path in an
// empty grid.
double OctileDistance(const Eigen::Vector2i& a, const Eigen::Vector2i& b, double resolution) {
  const int dx = std::abs(a.x() - b.x());
  const int dy = std::abs(a.y() - b.y());
  return resolution * (std::max(dx, dy) + (kSqrt2 - 1.0) * std::min(dx, dy));
}

struct OpenEntry {
  double f;
  int index;
  bool operator>(const OpenEntry& other) const { return f > other.f; }
};

GridPath TracePath(const Costmap& costmap, const std::vector<int>& parent, int goal_index,
                   double cost) {
  GridPath path;
  path.cost = cost;
  for (int i = goal_index; i >= 0; i = parent[static_cast<std::size_t>(i)]) {
    path.cells.emplace_back(i % costmap.width, i / costmap.width);
  }
  std::reverse(path.cells.begin(), path.cells.end());
  for (std::size_t i = 1; i < path.cells.size(); ++i) {
    path.length_meters += (path.cells[i] - path.cells[i - 1]).cast<double>().norm();
  }
  path.length_meters *= costmap.resolution;
  return path;
}

}  // namespace

bool AStarOptions::Validate(std::string* error) const {
  if (!(cost_weight >= 0.0)) {
    *error = "cost weight must be >= 0";
    return false;
  }
  return true;
}

double StepCost(const Costmap& costmap, const Eigen::Vector2i& from, const Eigen::Vector2i& to,
                const AStarOptions& options) {
  if (!costmap.Traversable(to)) return kInfinity;
  const Eigen::Vector2i d = to - from;
  SEMCHAIN_CHECK(std::abs(d.x()) <= 1 && std::abs(d.y()) <= 1 && d != Eigen::Vector2i::Zero());
  const bool diagonal = d.x() != 0 && d.y() != 0;
  if (diagonal && !options.allow_corner_cutting &&
      (!costmap.Traversable({to.x(), from.y()}) || !costmap.Traversable({from.x(), to.y()}))) {
    return kInfinity;
  }
  const double length = costmap.resolution * (diagonal ? kSqrt2 : 1.0);
  return length * (1.0 + options.cost_weight * costmap.At(to) / (kInscribedCost - 1.0));
}

std::optional<GridPath> PlanGridPath(const Costmap& costmap, const Eigen::Vector2i& start,
                                     const Eigen::Vector2i& goal, const AStarOptions& options) {
  if (!costmap.Traversable(start) || !costmap.Traversable(goal)) return std::nullopt;
  const std::size_t cells = static_cast<std::size_t>(costmap.width) * costmap.height;
  std::vector<double> g(cells, kInfinity);
  std::vector<int> parent(cells, -1);
  std::vector<std::uint8_t> closed(cells, 0);
  const auto index_of = [&](const Eigen::Vector2i& c) { return c.y() * costmap.width + c.x(); };
  std::priority_queue<OpenEntry, std::vector<OpenEntry>, std::greater<>> open;
  const int start_index = index_of(start);
  const int goal_index = index_of(goal);
  g[static_cast<std::size_t>(start_index)] = 0.0;
  open.push({OctileDistance(start, goal, costmap.resolution), start_index});
  while (!open.empty()) {
    const int current = open.top().index;
    open.pop();
    if (closed[static_cast<std::size_t>(current)]) continue;  // a stale queue entry
    closed[static_cast<std::size_t>(current)] = 1;
    const double g_current = g[static_cast<std::size_t>(current)];
    if (current == goal_index) return TracePath(costmap, parent, goal_index, g_current);
    const Eigen::Vector2i cell(current % costmap.width, current / costmap.width);
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector2i next(cell.x() + kDx[k], cell.y() + kDy[k]);
      if (!costmap.Contains(next)) continue;
      const int next_index = index_of(next);
      if (closed[static_cast<std::size_t>(next_index)]) continue;
      const double step = StepCost(costmap, cell, next, options);
      if (step == kInfinity) continue;
      const double g_next = g_current + step;
      if (g_next >= g[static_cast<std::size_t>(next_index)]) continue;
      g[static_cast<std::size_t>(next_index)] = g_next;
      parent[static_cast<std::size_t>(next_index)] = current;
      open.push({g_next + OctileDistance(next, goal, costmap.resolution), next_index});
    }
  }
  return std::nullopt;
}

}  // namespace semchain::planning
