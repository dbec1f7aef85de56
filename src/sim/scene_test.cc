#include "sim/scene.h"

#include <gtest/gtest.h>

#include "core/angles.h"

namespace semchain::sim {
namespace {

World SquareRoom() {
  World world;
  world.walls = {{{0, 0}, {10, 0}, {10, 6}, {0, 6}, {0, 0}}};
  world.wall_height = 2.5;
  return world;
}

Solid Box(double x, double y, double width, double depth, double height) {
  return MakeBoxSolid("cabinet", x, y, width, depth, height);
}

TEST(SceneTest, WallAtKnownDistance) {
  const Scene scene(SquareRoom());
  const auto hit = scene.CastAtHeight({2.0, 3.0}, 0.0, 20.0, 0.2);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->distance, 8.0, 1e-12);
  EXPECT_EQ(hit->surface.kind, SurfaceRef::Kind::kWall);
  EXPECT_TRUE(hit->normal.isApprox(Eigen::Vector2d(-1, 0)));
  // 45 degrees towards the corner region: hits the top wall y = 6 at x = 5.
  const auto diagonal = scene.CastAtHeight({2.0, 3.0}, kPi / 4.0, 20.0, 0.2);
  ASSERT_TRUE(diagonal.has_value());
  EXPECT_NEAR(diagonal->distance, 3.0 * std::sqrt(2.0), 1e-12);
  EXPECT_FALSE(scene.CastAtHeight({2.0, 3.0}, 0.0, 7.5, 0.2).has_value());
}

TEST(SceneTest, NearBoxOccludesFarBox) {
  World world = SquareRoom();
  world.objects.push_back(Box(5.0, 3.0, 1.0, 1.0, 1.0));  // front face at x = 4.5
  world.objects.push_back(Box(7.0, 3.0, 1.0, 1.0, 1.0));
  const Scene scene(world);
  const auto hit = scene.CastAtHeight({2.0, 3.0}, 0.0, 20.0, 0.5);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->distance, 2.5, 1e-12);
  EXPECT_EQ(hit->surface, (SurfaceRef{SurfaceRef::Kind::kObject, 0}));
  const auto all = scene.CastAll({2.0, 3.0}, 0.0, 20.0);
  ASSERT_EQ(all.size(), 5u);  // two faces of each box, then the wall
  EXPECT_NEAR(all[2].distance, 4.5, 1e-12);
  EXPECT_EQ(all[2].surface.index, 1);
}

TEST(SceneTest, ObjectBelowTheScanPlaneIsInvisibleToTheLidar) {
  World world = SquareRoom();
  world.obstacles.push_back(Box(5.0, 3.0, 0.4, 0.4, 0.13));
  world.obstacles.back().class_name.clear();
  const Scene scene(world);
  const auto at_lidar = scene.CastAtHeight({2.0, 3.0}, 0.0, 20.0, 0.19);
  ASSERT_TRUE(at_lidar.has_value());
  EXPECT_EQ(at_lidar->surface.kind, SurfaceRef::Kind::kWall);
  const auto low = scene.CastAtHeight({2.0, 3.0}, 0.0, 20.0, 0.05);
  ASSERT_TRUE(low.has_value());
  EXPECT_NEAR(low->distance, 2.8, 1e-12);
}

TEST(SceneTest, CircleEntryPointAndOccupancy) {
  World world = SquareRoom();
  Solid bucket;
  bucket.class_name = "bucket";
  bucket.footprint.shape = Footprint::Shape::kCircle;
  bucket.footprint.center = {5.0, 3.0};
  bucket.footprint.radius = 0.25;
  bucket.height = 0.4;
  world.objects.push_back(bucket);
  const Scene scene(world);
  const auto hit = scene.CastAtHeight({2.0, 3.0}, 0.0, 20.0, 0.19);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->distance, 2.75, 1e-12);
  EXPECT_TRUE(scene.IsOccupied({5.1, 3.0}, 0.0));
  EXPECT_TRUE(scene.IsOccupied({0.1, 3.0}, 0.2));
  EXPECT_FALSE(scene.IsOccupied({2.0, 3.0}, 0.2));
}

TEST(SceneTest, PolygonContainment) {
  const std::vector<Eigen::Vector2d> region = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  EXPECT_TRUE(PolygonContains(region, {1.0, 0.5}));
  EXPECT_FALSE(PolygonContains(region, {2.5, 0.5}));
}

}  // namespace
}  // namespace semchain::sim
