// Every bundled world in worlds/ loads, is geometrically sound, and its mapping route can be
// driven; the worlds modelled on the papers have the properties they are there for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "core/angles.h"
#include "sim/lidar.h"
#include "sim/route_follower.h"
#include "sim/scene.h"
#include "sim/world_io.h"

namespace semchain::sim {
namespace {

namespace fs = std::filesystem;

const fs::path kWorlds = fs::path(SEMCHAIN_SOURCE_DIR) / "worlds";

std::vector<fs::path> BundledWorlds() {
  std::vector<fs::path> paths;
  for (const auto& entry : fs::directory_iterator(kWorlds)) {
    if (entry.path().extension() == ".yaml") paths.push_back(entry.path());
  }
  std::sort(paths.begin(), paths.end());
  return paths;
}

World Load(const std::string& name) {
  const Result<World> world = LoadWorld(kWorlds / (name + ".yaml"));
  EXPECT_TRUE(world.ok()) << world.status().message();
  return world.ok() ? *world : World{};
}

TEST(WorldsTest, TheSixWorldsAreBundled) {
  std::vector<std::string> names;
  for (const fs::path& path : BundledWorlds()) names.push_back(path.stem().string());
  for (const char* name : {"two_similar_rooms", "two_similar_rooms_changed", "long_corridor",
                           "lab_loop", "low_obstacles", "furnished_flat"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  }
}

// The figures of the first five worlds were measured with single-prism objects; the flat has
// all ten classes of seed 000, each built of its parts.
TEST(WorldsTest, FurnishedFlatHasAllTenClassesBuiltOfParts) {
  const World flat = Load("furnished_flat");
  std::set<std::string> classes;
  for (const Solid& solid : flat.objects) {
    classes.insert(solid.class_name);
    EXPECT_EQ(solid.shape, ObjectShape::kParts) << solid.class_name;
    EXPECT_GE(solid.parts.size(), 3u) << solid.class_name;
  }
  EXPECT_EQ(classes.size(), 10u);
  for (const char* name : {"two_similar_rooms", "lab_loop", "long_corridor"}) {
    for (const Solid& solid : Load(name).objects) EXPECT_EQ(solid.shape, ObjectShape::kPrism);
  }
}

TEST(WorldsTest, EveryWorldIsValidAndItsRouteCanBeDriven) {
  for (const fs::path& path : BundledWorlds()) {
    SCOPED_TRACE(path.filename().string());
    const Result<World> world = LoadWorld(path);
    ASSERT_TRUE(world.ok()) << world.status().message();
    EXPECT_EQ(world->name, path.stem().string());
    // Objects inside the walls and off them, start and route ≥ 0.3 m from every surface.
    const Status valid = ValidateWorld(*world, path.filename().string(), 0.3);
    EXPECT_TRUE(valid.ok()) << valid.message();
    EXPECT_DOUBLE_EQ(world->robot.scan_rate_hz, 10.0);
    // The mapping route closes a loop, and the robot drives it without touching anything.
    ASSERT_GE(world->mapping_route.size(), 4u);
    EXPECT_LT((world->mapping_route.back() - world->mapping_route.front()).norm(), 0.5);
    const Scene scene(*world);
    const auto samples = GenerateTrajectory(scene, world->robot, RouteSpec{}, world->robot.start);
    ASSERT_TRUE(samples.ok()) << samples.status().message();
    EXPECT_LT((samples->back().pose.translation() - world->mapping_route.back()).norm(), 0.03);
    // The trial region is a polygon inside the walls with free space in it.
    ASSERT_GE(world->trial_region.size(), 3u);
    int free = 0;
    for (double x = 0.05; x < 40.0; x += 0.25) {
      for (double y = 0.05; y < 10.0; y += 0.25) {
        const Eigen::Vector2d p(x, y);
        if (PolygonContains(world->trial_region, p) && !scene.IsOccupied(p, 0.25)) ++free;
      }
    }
    EXPECT_GT(free, 20);
  }
}

double Distance(const World& world, int a, int b) {
  return (world.objects[a].footprint.center - world.objects[b].footprint.center).norm();
}

// Seed 001 Table 1: the neighbour distances of the lab's loop of objects.
TEST(WorldsTest, LabLoopMatchesTheChainOfSeed001Table1) {
  const World world = Load("lab_loop");
  ASSERT_EQ(world.objects.size(), 12u);
  const std::vector<std::string> classes = {"cabinet", "bucket",  "stool",   "cabinet",
                                            "cabinet", "cabinet", "cabinet", "stool",
                                            "cabinet", "cabinet", "door",    "cabinet"};
  const double table[12] = {0.474, 1.632, 0.326, 1.273, 0.463, 0.406,
                            0.527, 0.364, 0.306, 0.389, 0.416, 0.460};
  for (int i = 0; i < 12; ++i) {
    EXPECT_EQ(world.objects[i].class_name, classes[i]) << i;
    const int next = (i + 1) % 12;
    // A 0.7 m door in the wall line cannot have its neighbours' centres as close as the
    // table's (see the world file); every other link is within 2 cm.
    const bool door_link = i == 9 || i == 10;
    EXPECT_NEAR(Distance(world, i, next), table[i], door_link ? 0.16 : 0.02) << i << "→" << next;
  }
  // The loop goes clockwise around the closet: the signed area of the centres is negative.
  double area = 0.0;
  for (int i = 0; i < 12; ++i) {
    const Eigen::Vector2d& p = world.objects[i].footprint.center;
    const Eigen::Vector2d& q = world.objects[(i + 1) % 12].footprint.center;
    area += p.x() * q.y() - q.x() * p.y();
  }
  EXPECT_LT(area, 0.0);
}

// Seed 004 §3.1: with the lidar at 0.19 m, obstacle A (0.27 m) is seen and B (0.13 m) is not.
TEST(WorldsTest, LowObstaclesHideBFromTheLidar) {
  World world = Load("low_obstacles");
  ASSERT_EQ(world.obstacles.size(), 2u);
  EXPECT_DOUBLE_EQ(world.robot.lidar.height, 0.19);
  world.robot.lidar.noise_std = 0.0;
  const Scene scene(world);
  Rng rng = MakeRng(0);
  // From (1, 2) facing +x, the beam straight ahead looks along y = 2 through A (face x = 2.35)
  // and B (3.85).
  const LaserScan scan = SimulateScan(scene, world.robot.lidar, Pose2(1.0, 2.0, 0.0), 0.0, rng);
  const auto ahead = static_cast<std::size_t>(std::lround(-scan.angle_min / scan.angle_increment));
  ASSERT_NEAR(scan.BeamAngle(ahead), 0.0, 1e-12);
  EXPECT_NEAR(scan.ranges[ahead], 1.35, 1e-9);
  const LaserScan past_a = SimulateScan(scene, world.robot.lidar, Pose2(3.2, 2.0, 0.0), 0.0, rng);
  EXPECT_NEAR(past_a.ranges[ahead], 6.0 - 3.2, 1e-9);  // B is invisible: the wall at x = 6
}

// A changed world keeps the original's objects (so a map of one serves the other): the same
// classes in the same places, rendered alike.
void ExpectSameObjects(const World& original, const World& changed) {
  ASSERT_EQ(original.objects.size(), changed.objects.size());
  for (std::size_t i = 0; i < original.objects.size(); ++i) {
    EXPECT_EQ(original.objects[i].class_name, changed.objects[i].class_name);
    EXPECT_EQ(original.objects[i].footprint.center, changed.objects[i].footprint.center);
    EXPECT_EQ(original.objects[i].texture_seed, changed.objects[i].texture_seed);
  }
}

// Seed 000 §4.2: the changed world keeps the original's objects (so a map of one serves the
// other) and adds the white column next to the bucket.
TEST(WorldsTest, ChangedRoomsKeepTheObjectsAndHideTheBucket) {
  const World original = Load("two_similar_rooms");
  const World changed = Load("two_similar_rooms_changed");
  ExpectSameObjects(original, changed);
  EXPECT_NE(original.walls[0], changed.walls[0]);  // the moved wall section
  ASSERT_EQ(changed.obstacles.size(), 1u);
  const Solid& column = changed.obstacles[0];
  EXPECT_TRUE(column.class_name.empty());
  // The column stands between the bucket and the middle of room A, taller than the camera.
  const auto bucket = std::find_if(changed.objects.begin(), changed.objects.end(),
                                   [](const Solid& s) { return s.class_name == "bucket"; });
  ASSERT_NE(bucket, changed.objects.end());
  const Scene scene(changed);
  const Eigen::Vector2d middle(3.0, 3.5);
  const Eigen::Vector2d to_bucket = bucket->footprint.center - middle;
  const auto hits = scene.CastAll(middle, std::atan2(to_bucket.y(), to_bucket.x()), 10.0);
  ASSERT_FALSE(hits.empty());
  EXPECT_EQ(hits.front().surface.kind, SurfaceRef::Kind::kObstacle);
  EXPECT_GT(column.height, changed.robot.camera.height);
}

// The bag-of-words world pair: the changed hall adds one column, which hides bay 1's cabinet
// from every corner of the trial region while stool and bucket stay in sight; bay 2 is bay 1
// turned half about the hall's centre with a chair in the cabinet's place.
TEST(WorldsTest, OccludedCorridorHidesTheCabinetBetweenLookAlikePairs) {
  const World original = Load("occluded_corridor");
  const World changed = Load("occluded_corridor_changed");
  ExpectSameObjects(original, changed);
  EXPECT_TRUE(original.obstacles.empty());
  ASSERT_EQ(changed.obstacles.size(), 1u);
  EXPECT_GT(changed.obstacles[0].height, changed.robot.camera.height);
  auto find = [&](const std::string& name, bool north) {
    for (std::size_t i = 0; i < changed.objects.size(); ++i) {
      const Solid& s = changed.objects[i];
      if (s.class_name == name && (s.footprint.center.y() > 3.0) == north)
        return static_cast<int>(i);
    }
    return -1;
  };
  const int cabinet = find("cabinet", true), stool = find("stool", true),
            bucket = find("bucket", true);
  ASSERT_GE(cabinet, 0);
  ASSERT_GE(stool, 0);
  ASSERT_GE(bucket, 0);
  // Bay 2: bay 1 turned half about (20, 3), the chair where the cabinet is.
  const Eigen::Vector2d centre(20.0, 3.0);
  for (const auto& [bay_1_object, bay_2_class] : std::vector<std::pair<int, std::string>>{
           {stool, "stool"}, {cabinet, "chair"}, {bucket, "bucket"}}) {
    const int image = find(bay_2_class, false);
    ASSERT_GE(image, 0) << bay_2_class;
    const Eigen::Vector2d turned = 2.0 * centre - changed.objects[bay_1_object].footprint.center;
    EXPECT_LT((changed.objects[image].footprint.center - turned).norm(), 0.12) << bay_2_class;
  }
  const Scene scene(changed);
  auto first_hit = [&](const Eigen::Vector2d& from, int object) {
    const Eigen::Vector2d to = changed.objects[object].footprint.center - from;
    const auto hits = scene.CastAll(from, std::atan2(to.y(), to.x()), 20.0);
    return hits.empty() ? SurfaceRef{} : hits.front().surface;
  };
  for (const Eigen::Vector2d& corner : changed.trial_region) {
    EXPECT_EQ(first_hit(corner, cabinet).kind, SurfaceRef::Kind::kObstacle);
    for (const int seen : {stool, bucket}) {
      const SurfaceRef hit = first_hit(corner, seen);
      EXPECT_EQ(hit.kind, SurfaceRef::Kind::kObject);
      EXPECT_EQ(hit.index, seen);
    }
  }
}

}  // namespace
}  // namespace semchain::sim
