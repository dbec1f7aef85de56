#include "planning/route.h"

#include <gtest/gtest.h>

#include "planning/path_io.h"
#include "planning/testing/test_maps.h"

namespace semchain::planning {
namespace {

using testing::MapFromText;

// A 3 m × 2 m room (0.1 m cells) with walls around it and a pillar in its middle.
Costmap Room(const std::vector<Polygon>& keepout = {}) {
  std::vector<std::string> rows(20, "#" + std::string(28, '.') + "#");
  rows.front() = rows.back() = std::string(30, '#');
  for (int r = 9; r <= 10; ++r) rows[static_cast<std::size_t>(r)].replace(14, 2, "##");
  CostmapOptions options;
  options.robot_radius_meters = 0.2;
  options.inflation_radius_meters = 0.4;
  const Result<Costmap> costmap = BuildCostmap(MapFromText(rows), keepout, options);
  EXPECT_TRUE(costmap.ok());
  return *costmap;
}

TEST(RouteTest, VisitsTheGoalsInOrder) {
  const Costmap costmap = Room();
  const Result<Route> route = PlanRoute(costmap, {{0.55, 0.55}, {2.45, 0.55}, {2.45, 1.45}});
  ASSERT_TRUE(route.ok()) << route.status().message();
  ASSERT_EQ(route->leg_ends.size(), 2u);
  EXPECT_TRUE(route->points.front().isApprox(Eigen::Vector2d(0.55, 0.55)));
  EXPECT_TRUE(route->points[route->leg_ends[0]].isApprox(Eigen::Vector2d(2.45, 0.55)));
  EXPECT_TRUE(route->points.back().isApprox(Eigen::Vector2d(2.45, 1.45)));
  EXPECT_EQ(route->leg_ends[1], route->points.size() - 1);
  double length = 0.0;
  for (std::size_t i = 1; i < route->points.size(); ++i) {
    const double step = (route->points[i] - route->points[i - 1]).norm();
    EXPECT_LT(step, 0.1 * std::sqrt(2.0) + 1e-9);  // 8-connected, no repeated cell
    EXPECT_GT(step, 0.05);
    length += step;
  }
  EXPECT_NEAR(route->length_meters, length, 1e-9);
  // Both legs are at least as long as the straight lines 1.9 m and 0.9 m.
  EXPECT_GE(route->length_meters, 2.8 - 1e-9);
  EXPECT_GE(route->cost, route->length_meters);
  const std::string json = RouteJson(*route);
  EXPECT_EQ(json.rfind("{\"cost\":", 0), 0u);
  EXPECT_NE(json.find("\"length_m\":"), std::string::npos);
  EXPECT_NE(json.find("\"path\":[[0.55"), std::string::npos);
}

TEST(RouteTest, RejectsBadPointsWithOneClearMessage) {
  const Costmap costmap = Room({{{2.0, 1.5}, {2.6, 1.5}, {2.6, 1.85}, {2.0, 1.85}}});
  const auto error = [&](const std::vector<Eigen::Vector2d>& points) {
    const Result<Route> route = PlanRoute(costmap, points);
    return route.ok() ? std::string("ok") : route.status().message();
  };
  EXPECT_NE(error({{-1.0, 0.5}, {1.0, 0.5}}).find("start (-1.000, 0.500) is outside the map"),
            std::string::npos);
  EXPECT_NE(error({{0.55, 0.55}, {1.5, 1.0}}).find("goal 1 (1.500, 1.000) is inside an obstacle"),
            std::string::npos);
  EXPECT_NE(error({{0.55, 0.55}, {1.0, 0.55}, {2.3, 1.7}})
                .find("goal 2 (2.300, 1.700) is inside "
                      "a keep-out zone"),
            std::string::npos);
  EXPECT_NE(error({{0.15, 0.55}, {1.0, 0.55}}).find("closer to an obstacle"), std::string::npos);
  EXPECT_NE(error({{0.55, 0.55}}).find("at least one goal"), std::string::npos);
}

TEST(RouteTest, UnreachableGoal) {
  // A wall splits the room in two.
  std::vector<std::string> rows(10, std::string(20, '.'));
  for (auto& row : rows) row[10] = '#';
  CostmapOptions options;
  options.robot_radius_meters = 0.0;
  options.inflation_radius_meters = 0.0;
  const Result<Costmap> costmap = BuildCostmap(MapFromText(rows), {}, options);
  const Result<Route> route = PlanRoute(*costmap, {{0.25, 0.5}, {1.75, 0.5}});
  ASSERT_FALSE(route.ok());
  EXPECT_EQ(route.status().message(),
            "no path from start (0.250, 0.500) to goal 1 (1.750, 0.500): unreachable");
}

}  // namespace
}  // namespace semchain::planning
