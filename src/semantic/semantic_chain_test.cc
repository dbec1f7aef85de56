#include "semantic/semantic_chain.h"

#include <gtest/gtest.h>

namespace semchain::semantic {
namespace {

SemanticObject Object(int id, const std::string& class_name, double x, double y) {
  SemanticObject object;
  object.id = id;
  object.class_name = class_name;
  object.center = Eigen::Vector2d(x, y);
  for (const auto& [dx, dy] :
       {std::pair{0.1, 0.1}, std::pair{-0.1, 0.1}, std::pair{-0.1, -0.1}, std::pair{0.1, -0.1}}) {
    object.footprint.emplace_back(x + dx, y + dy);
  }
  return object;
}

// Free cells inside the given rectangles (metres), walls (occupied) around them, unknown
// elsewhere; 0.05 m cells from the origin.
mapping::MapImage MakeMap(double width, double height,
                          const std::vector<std::array<double, 4>>& free_rectangles) {
  mapping::MapImage map;
  map.resolution = 0.05;
  map.width = static_cast<int>(width / map.resolution);
  map.height = static_cast<int>(height / map.resolution);
  map.cells.assign(static_cast<std::size_t>(map.width * map.height), 100);
  for (const auto& r : free_rectangles) {
    for (int y = 0; y < map.height; ++y) {
      for (int x = 0; x < map.width; ++x) {
        const double cx = (x + 0.5) * map.resolution;
        const double cy = (y + 0.5) * map.resolution;
        if (cx > r[0] && cx < r[2] && cy > r[1] && cy < r[3]) {
          map.cells[static_cast<std::size_t>(y * map.width + x)] = 0;
        }
      }
    }
  }
  return map;
}

TEST(SemanticChainTest, ClockwiseFromTheDoor) {
  // Around (0, 0): a door in the west, a cabinet north, a bucket east, a stool south.
  const std::vector<SemanticObject> objects = {Object(7, "bucket", 2, 0), Object(3, "stool", 0, -2),
                                               Object(5, "cabinet", 0, 2),
                                               Object(9, "door", -2, 0)};
  EXPECT_EQ(ClockwiseOrder(objects, Eigen::Vector2d::Zero()), (std::vector<int>{9, 5, 7, 3}));
  // Without a door: from the first object clockwise of north.
  const std::vector<SemanticObject> no_door(objects.begin(), objects.begin() + 3);
  EXPECT_EQ(ClockwiseOrder(no_door, Eigen::Vector2d::Zero()), (std::vector<int>{5, 7, 3}));
}

TEST(SemanticChainTest, LinksJoinNeighboursAndCloseTheLoop) {
  const std::vector<SemanticObject> objects = {Object(1, "door", 0, 0), Object(2, "cabinet", 3, 4),
                                               Object(3, "bucket", 3, 0)};
  const SemanticChain chain = MakeChain(4, {1, 2, 3}, objects);
  EXPECT_EQ(chain.region, 4);
  ASSERT_EQ(chain.links.size(), 3u);
  EXPECT_DOUBLE_EQ(chain.links[0].distance, 5.0);
  EXPECT_DOUBLE_EQ(chain.links[1].distance, 4.0);
  EXPECT_EQ(chain.links[2].from, 3);
  EXPECT_EQ(chain.links[2].to, 1);
  EXPECT_DOUBLE_EQ(chain.links[2].distance, 3.0);
  SemanticMap map;
  map.objects = objects;
  map.chains = {chain};
  ChainNeighbours neighbours;
  ASSERT_TRUE(FindChainNeighbours(map, 1, &neighbours));
  EXPECT_EQ(neighbours.upstream, 3);
  EXPECT_EQ(neighbours.downstream, 2);
  EXPECT_DOUBLE_EQ(neighbours.upstream_distance, 3.0);
}

TEST(SemanticChainTest, DoorwaysCutRegionsAndWallsBlockSight) {
  // Two 3 m × 3 m rooms joined by a 0.8 m doorway in the wall at x = 3.
  const mapping::MapImage map =
      MakeMap(6.2, 3.2, {{0.1, 0.1, 2.95, 3.1}, {3.05, 0.1, 6.1, 3.1}, {2.9, 1.2, 3.1, 2.0}});
  const RegionMap regions = SegmentRegions(map, ChainOptions());
  ASSERT_EQ(regions.count(), 2);
  EXPECT_NEAR(regions.centers[0].x(), 1.5, 0.2);
  EXPECT_NEAR(regions.centers[1].x(), 4.6, 0.2);
  // An object against the dividing wall belongs to the room it was seen from.
  const SemanticObject against_wall = Object(1, "cabinet", 3.2, 0.5);
  EXPECT_EQ(RegionOfViewed(regions, map, against_wall, {{5.0, 1.0}, {4.0, 2.0}}), 1);
  EXPECT_EQ(RegionOfViewed(regions, map, against_wall, {{1.0, 1.0}}), 0);

  SemanticMap semantic;
  semantic.objects = {Object(0, "door", 0.5, 0.5), Object(1, "cabinet", 2.5, 0.5),
                      Object(2, "bucket", 3.5, 0.5), Object(3, "chair", 5.5, 2.5)};
  EXPECT_TRUE(MutuallyVisible(map, semantic.objects[0], semantic.objects[1]));
  EXPECT_FALSE(MutuallyVisible(map, semantic.objects[1], semantic.objects[2]));  // the wall
  BuildChainsAndNeighbours(map, ChainOptions(), {}, &semantic);
  ASSERT_EQ(semantic.chains.size(), 2u);
  EXPECT_EQ(semantic.chains[0].order, (std::vector<int>{0, 1}));
  EXPECT_EQ(semantic.chains[1].order.size(), 2u);
  for (const ChainLink& link : semantic.neighbours) {
    EXPECT_FALSE((link.from == 1 && link.to == 2)) << "neighbours through a wall";
  }
}

}  // namespace
}  // namespace semchain::semantic
