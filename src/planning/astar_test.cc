#include "planning/astar.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <queue>
#include <random>

#include "planning/testing/test_maps.h"

namespace semchain::planning {
namespace {

using testing::MapFromText;
using testing::RandomMap;

Costmap Build(const mapping::MapImage& map, const std::vector<Polygon>& keepout = {},
              CostmapOptions options = {}) {
  const Result<Costmap> costmap = BuildCostmap(map, keepout, options);
  EXPECT_TRUE(costmap.ok()) << costmap.status().message();
  return *costmap;
}

// Dijkstra's algorithm with the same step costs: the reference minimum cost.
double DijkstraCost(const Costmap& costmap, const Eigen::Vector2i& start,
                    const Eigen::Vector2i& goal, const AStarOptions& options) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> dist(static_cast<std::size_t>(costmap.width * costmap.height), inf);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  const auto index = [&](const Eigen::Vector2i& c) { return c.y() * costmap.width + c.x(); };
  dist[static_cast<std::size_t>(index(start))] = 0.0;
  queue.push({0.0, index(start)});
  while (!queue.empty()) {
    const auto [d, i] = queue.top();
    queue.pop();
    if (d > dist[static_cast<std::size_t>(i)]) continue;
    const Eigen::Vector2i cell(i % costmap.width, i / costmap.width);
    if (cell == goal) return d;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const Eigen::Vector2i next = cell + Eigen::Vector2i(dx, dy);
        if ((dx == 0 && dy == 0) || !costmap.Contains(next)) continue;
        const double nd = d + StepCost(costmap, cell, next, options);
        if (nd < dist[static_cast<std::size_t>(index(next))]) {
          dist[static_cast<std::size_t>(index(next))] = nd;
          queue.push({nd, index(next)});
        }
      }
    }
  }
  return inf;
}

TEST(AStarTest, StraightLineInFreeSpace) {
  const Costmap costmap = Build(MapFromText(std::vector<std::string>(10, std::string(30, '.'))));
  const auto path = PlanGridPath(costmap, {2, 5}, {22, 5});
  ASSERT_TRUE(path.has_value());
  EXPECT_EQ(path->cells.size(), 21u);
  EXPECT_NEAR(path->length_meters, 2.0, 1e-9);
  EXPECT_NEAR(path->cost, 2.0, 1e-9);  // free cells cost their length only
  // A diagonal: 5 steps of √2 cells.
  const auto diagonal = PlanGridPath(costmap, {2, 2}, {7, 7});
  ASSERT_TRUE(diagonal.has_value());
  EXPECT_NEAR(diagonal->length_meters, 0.5 * std::sqrt(2.0), 1e-9);
}

TEST(AStarTest, DetoursAroundAWallAndFailsWhenSealed) {
  std::vector<std::string> rows(15, std::string(30, '.'));
  for (int r = 0; r < 12; ++r) rows[static_cast<std::size_t>(r)][15] = '#';  // open at the bottom
  CostmapOptions options;
  options.robot_radius_meters = 0.1;
  options.inflation_radius_meters = 0.1;
  const Costmap open = Build(MapFromText(rows), {}, options);
  const auto path = PlanGridPath(open, {5, 10}, {25, 10});
  ASSERT_TRUE(path.has_value());
  for (const Eigen::Vector2i& cell : path->cells) EXPECT_LT(open.At(cell), kInscribedCost);
  EXPECT_GT(path->length_meters, 2.0);  // longer than the straight line through the wall
  rows[12][15] = rows[13][15] = rows[14][15] = '#';
  const Costmap sealed = Build(MapFromText(rows), {}, options);
  EXPECT_FALSE(PlanGridPath(sealed, {5, 10}, {25, 10}).has_value());
  EXPECT_FALSE(PlanGridPath(sealed, {5, 10}, {15, 10}).has_value());  // goal in the wall
}

TEST(AStarTest, NoCornerCutting) {
  // (0, 1) and (1, 0) are obstacles touching at a corner: from (0, 0) the only way out is the
  // diagonal between them.
  const Costmap costmap =
      Build(MapFromText({"...", "#..", ".#."}), {}, CostmapOptions{0.0, 0.0, 3.0});
  EXPECT_FALSE(PlanGridPath(costmap, {0, 0}, {2, 2}).has_value());
  AStarOptions cutting;
  cutting.allow_corner_cutting = true;
  const auto path = PlanGridPath(costmap, {0, 0}, {2, 2}, cutting);
  ASSERT_TRUE(path.has_value());
  EXPECT_EQ(path->cells.size(), 3u);
  EXPECT_EQ(path->cells[1], Eigen::Vector2i(1, 1));
}

// Property: on seeded random maps A*'s cost equals Dijkstra's, and no path enters a lethal,
// inscribed, unknown or keep-out cell.
TEST(AStarTest, CostEqualsDijkstraOnRandomMaps) {
  std::mt19937_64 rng(20261121);
  int reachable = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int width = 30 + static_cast<int>(rng() % 40);
    const int height = 30 + static_cast<int>(rng() % 40);
    const double density = 0.02 + 0.06 * static_cast<double>(rng() % 100) / 100.0;
    const mapping::MapImage map = RandomMap(width, height, density, rng(), 0.05);
    CostmapOptions costmap_options;
    costmap_options.robot_radius_meters = 0.05 * static_cast<double>(rng() % 3);
    costmap_options.inflation_radius_meters = costmap_options.robot_radius_meters + 0.2;
    costmap_options.min_obstacle_cells = 0;
    const double cx = 0.05 * width / 2.0, cy = 0.05 * height / 2.0;
    const Polygon zone = {{cx - 0.2, cy - 0.3}, {cx + 0.3, cy - 0.1}, {cx, cy + 0.3}};
    const Costmap costmap = Build(map, {zone}, costmap_options);
    AStarOptions options;
    options.cost_weight = static_cast<double>(rng() % 5);
    options.allow_corner_cutting = trial % 4 == 3;
    for (int pair = 0; pair < 5; ++pair) {
      const Eigen::Vector2i start(static_cast<int>(rng() % width),
                                  static_cast<int>(rng() % height));
      const Eigen::Vector2i goal(static_cast<int>(rng() % width), static_cast<int>(rng() % height));
      if (!costmap.Traversable(start) || !costmap.Traversable(goal)) continue;
      const double reference = DijkstraCost(costmap, start, goal, options);
      const auto path = PlanGridPath(costmap, start, goal, options);
      ASSERT_EQ(path.has_value(), std::isfinite(reference)) << "trial " << trial;
      if (!path) continue;
      ++reachable;
      EXPECT_NEAR(path->cost, reference, 1e-9 * (1.0 + reference)) << "trial " << trial;
      ASSERT_EQ(path->cells.front(), start);
      ASSERT_EQ(path->cells.back(), goal);
      double cost = 0.0;
      for (std::size_t i = 0; i < path->cells.size(); ++i) {
        const Eigen::Vector2i& cell = path->cells[i];
        EXPECT_LT(costmap.At(cell), kInscribedCost) << "trial " << trial;
        EXPECT_FALSE(costmap.InKeepout(cell)) << "trial " << trial;
        if (i > 0) cost += StepCost(costmap, path->cells[i - 1], cell, options);
      }
      EXPECT_NEAR(cost, path->cost, 1e-9 * (1.0 + cost));  // the cells are a valid 8-path
    }
  }
  EXPECT_GT(reachable, 50);  // the property was exercised
}

}  // namespace
}  // namespace semchain::planning
