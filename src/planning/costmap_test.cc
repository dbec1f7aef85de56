#include "planning/costmap.h"

#include <gtest/gtest.h>

#include <cmath>

#include "planning/testing/test_maps.h"

namespace semchain::planning {
namespace {

using testing::MapFromText;

// A free 41 × 41 map (0.05 m cells) with one 3 × 3 obstacle block in the middle.
mapping::MapImage BlockMap() {
  std::vector<std::string> rows(41, std::string(41, '.'));
  for (int r = 19; r <= 21; ++r) rows[static_cast<std::size_t>(r)].replace(19, 3, "###");
  return MapFromText(rows, 0.05);
}

TEST(CostmapTest, InflationFollowsTheNav2Formula) {
  CostmapOptions options;  // radius 0.2 m, inflation 0.55 m, k = 3
  EXPECT_EQ(InflationCost(0.0, options), kLethalCost);
  EXPECT_EQ(InflationCost(0.2, options), kInscribedCost);
  EXPECT_EQ(InflationCost(0.3, options), static_cast<std::uint8_t>(252 * std::exp(-3.0 * 0.1)));
  EXPECT_EQ(InflationCost(0.55, options), static_cast<std::uint8_t>(252 * std::exp(-3.0 * 0.35)));
  EXPECT_EQ(InflationCost(0.56, options), kFreeCost);
  EXPECT_LT(InflationCost(0.2001, options), kInscribedCost);  // just outside: traversable
}

TEST(CostmapTest, CellsAreCostedByTheirDistanceToTheBlock) {
  const Result<Costmap> costmap = BuildCostmap(BlockMap(), {}, CostmapOptions{});
  ASSERT_TRUE(costmap.ok()) << costmap.status().message();
  EXPECT_EQ(costmap->removed_noise_cells, 0);
  CostmapOptions options;
  // Along the row through the block's centre the nearest obstacle cell is (21, 20).
  for (int x = 21; x < 41; ++x) {
    const double distance = (x - 21) * 0.05;
    EXPECT_EQ(costmap->At({x, 20}), InflationCost(distance, options)) << x;
  }
  // Diagonally from the corner (21, 21): Euclidean, not city-block, distance.
  EXPECT_EQ(costmap->At({24, 24}), InflationCost(std::sqrt(18.0) * 0.05, options));
  EXPECT_FALSE(costmap->Traversable({25, 20}));  // 0.2 m from the block
  EXPECT_TRUE(costmap->Traversable({26, 20}));   // 0.25 m
  EXPECT_EQ(costmap->At({0, 0}), kFreeCost);
}

TEST(CostmapTest, IsolatedNoiseCellsAreRemoved) {
  mapping::MapImage map = BlockMap();
  map.cells[static_cast<std::size_t>(5 * map.width + 5)] = 100;   // a lone cell
  map.cells[static_cast<std::size_t>(35 * map.width + 5)] = 100;  // a diagonal pair
  map.cells[static_cast<std::size_t>(36 * map.width + 6)] = 100;
  CostmapOptions options;
  options.min_obstacle_cells = 3;
  const Result<Costmap> costmap = BuildCostmap(map, {}, options);
  ASSERT_TRUE(costmap.ok());
  EXPECT_EQ(costmap->removed_noise_cells, 3);
  EXPECT_EQ(costmap->At({5, 5}), kFreeCost);
  EXPECT_EQ(costmap->At({5, 35}), kFreeCost);
  EXPECT_EQ(costmap->At({20, 20}), kLethalCost);  // the 9-cell block stays
  options.min_obstacle_cells = 0;
  const Result<Costmap> kept = BuildCostmap(map, {}, options);
  EXPECT_EQ(kept->At({5, 5}), kLethalCost);
  EXPECT_EQ(kept->At({6, 36}), kLethalCost);
}

TEST(CostmapTest, UnknownCellsFollowThePolicy) {
  const mapping::MapImage map = MapFromText({"...??", "...??", "....."}, 0.05);
  CostmapOptions options;
  options.robot_radius_meters = 0.0;
  options.inflation_radius_meters = 0.0;
  Result<Costmap> lethal = BuildCostmap(map, {}, options);
  EXPECT_EQ(lethal->At({4, 2}), kUnknownCost);
  EXPECT_FALSE(lethal->Traversable({4, 2}));
  EXPECT_EQ(lethal->At({2, 2}), kFreeCost);  // unknown cells are not inflated
  options.unknown = UnknownPolicy::kFree;
  Result<Costmap> free = BuildCostmap(map, {}, options);
  EXPECT_EQ(free->At({4, 2}), kFreeCost);
}

TEST(CostmapTest, KeepoutZonesAreLethalAndInflated) {
  const mapping::MapImage map = MapFromText(std::vector<std::string>(20, std::string(40, '.')));
  // A square zone over cells x 10..14, y 5..9 (0.1 m cells).
  const Polygon zone = {{1.02, 0.52}, {1.48, 0.52}, {1.48, 0.98}, {1.02, 0.98}};
  CostmapOptions options;
  const Result<Costmap> costmap = BuildCostmap(map, {zone}, options);
  ASSERT_TRUE(costmap.ok());
  for (int y = 5; y < 10; ++y) {
    for (int x = 10; x < 15; ++x) {
      EXPECT_TRUE(costmap->InKeepout({x, y})) << x << "," << y;
      EXPECT_EQ(costmap->At({x, y}), kLethalCost);
    }
  }
  EXPECT_FALSE(costmap->InKeepout({9, 7}));
  EXPECT_FALSE(costmap->InKeepout({15, 7}));
  EXPECT_EQ(costmap->At({16, 7}), kInscribedCost);  // 0.2 m from the zone's edge cell
  options.inflate_keepout = false;
  const Result<Costmap> bare = BuildCostmap(map, {zone}, options);
  EXPECT_EQ(bare->At({16, 7}), kFreeCost);
  EXPECT_EQ(bare->At({12, 7}), kLethalCost);
}

TEST(CostmapTest, RejectsRotatedMapsAndBadOptions) {
  mapping::MapImage map = BlockMap();
  map.origin.z() = 0.3;
  EXPECT_FALSE(BuildCostmap(map, {}).ok());
  CostmapOptions options;
  options.inflation_radius_meters = 0.1;  // below the robot radius
  const Result<Costmap> bad = BuildCostmap(BlockMap(), {}, options);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("inflation radius"), std::string::npos);
}

}  // namespace
}  // namespace semchain::planning
