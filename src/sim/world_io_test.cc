#include "sim/world_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/angles.h"
#include "sensors/detection.h"
#include "sim/world.h"

namespace semchain::sim {
namespace {

using ::testing::HasSubstr;

// Line numbers matter: the error tests below point at them.
constexpr char kValid[] = R"(name: tiny
seed: 7
walls:
  - [[0, 0], [6, 0], [6, 4], [0, 4], [0, 0]]
wall_height: 2.4
objects:
  - {class: door, x: 1.0, y: 0.0, yaw: 0, width: 0.9, depth: 0.05, height: 2.0}
  - {class: bucket, x: 5.0, y: 3.5, radius: 0.15, height: 0.4, color: [20, 90, 200]}
obstacles:
  - {x: 3.0, y: 2.0, radius: 0.1, height: 1.2}
robot:
  start: [1.0, 1.0, 1.5707963267948966]
  radius: 0.25
  lidar: {height: 0.19, beams: 90, fov_deg: 360, max_range: 8.0, noise_std: 0.02}
  camera: {height: 0.45, fov_deg: 70, width: 160, height_px: 120, max_range: 5.0}
  odometry_noise: [0.01, 0.02, 0.03, 0.04]
  scan_rate_hz: 10
  frame_rate_hz: 2
detection: {miss_probability: 0.1, false_positives_per_frame: 0}
mapping_route: [[1, 1], [5, 1], [5, 3], [1, 3], [1, 1]]
trial_region: [[3, 0.5], [5.5, 0.5], [5.5, 3.5], [3, 3.5]]
)";

// The valid world with line 'line' (1-based) replaced by 'text'.
std::string WithLine(int line, const std::string& text) {
  std::string yaml = kValid;
  std::size_t begin = 0;
  for (int i = 1; i < line; ++i) begin = yaml.find('\n', begin) + 1;
  const std::size_t end = yaml.find('\n', begin);
  return yaml.replace(begin, end - begin, text);
}

TEST(WorldIoTest, ParsesEverySection) {
  const Result<World> world = ParseWorld(kValid, "tiny.yaml");
  ASSERT_TRUE(world.ok()) << world.status().message();
  EXPECT_EQ(world->name, "tiny");
  EXPECT_EQ(world->seed, 7u);
  ASSERT_EQ(world->walls.size(), 1u);
  EXPECT_EQ(world->walls[0].size(), 5u);
  EXPECT_DOUBLE_EQ(world->wall_height, 2.4);
  ASSERT_EQ(world->objects.size(), 2u);
  EXPECT_EQ(world->objects[0].class_name, "door");
  EXPECT_EQ(world->objects[0].footprint.shape, Footprint::Shape::kBox);
  EXPECT_DOUBLE_EQ(world->objects[0].footprint.width, 0.9);
  EXPECT_EQ(world->objects[1].footprint.shape, Footprint::Shape::kCircle);
  EXPECT_EQ(world->objects[1].color[2], 200);
  ASSERT_EQ(world->obstacles.size(), 1u);
  EXPECT_TRUE(world->obstacles[0].class_name.empty());
  EXPECT_NEAR(world->robot.start.theta, kPi / 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(world->robot.radius, 0.25);
  EXPECT_EQ(world->robot.lidar.beams, 90);
  EXPECT_DOUBLE_EQ(world->robot.lidar.noise_std, 0.02);
  EXPECT_EQ(world->robot.camera.width, 160);
  EXPECT_DOUBLE_EQ(world->robot.odometry_noise[3], 0.04);
  EXPECT_DOUBLE_EQ(world->robot.odometry_scale_error.distance, 0.0);  // unbiased by default
  EXPECT_DOUBLE_EQ(world->detection.miss_probability, 0.1);
  EXPECT_DOUBLE_EQ(world->detection.confusion_probability, 0.02);  // default kept
  EXPECT_EQ(world->mapping_route.size(), 5u);
  EXPECT_EQ(world->trial_region.size(), 4u);
  EXPECT_EQ(world->classes, DefaultClassNames());
  // Every solid gets its own texture seed.
  EXPECT_NE(world->objects[0].texture_seed, world->objects[1].texture_seed);
  EXPECT_NE(world->objects[0].texture_seed, world->obstacles[0].texture_seed);
  EXPECT_TRUE(ValidateWorld(*world, "tiny.yaml").ok());
}

TEST(WorldIoTest, UnknownKeyNamesFileLineAndPath) {
  const Result<World> world =
      ParseWorld(WithLine(14, "  lidar: {hieght: 0.19, beams: 90}"), "typo.yaml");
  ASSERT_FALSE(world.ok());
  EXPECT_THAT(world.status().message(), HasSubstr("typo.yaml:14: robot.lidar.hieght: unknown key"));
}

TEST(WorldIoTest, MalformedNumberNamesFileLineAndPath) {
  const Result<World> world = ParseWorld(
      WithLine(8, "  - {class: bucket, x: 5.0, y: 3.5, radius: 0.1.5, height: 0.4}"), "bad.yaml");
  ASSERT_FALSE(world.ok());
  EXPECT_THAT(world.status().message(), HasSubstr("bad.yaml:8: objects[1].radius:"));
  EXPECT_THAT(world.status().message(), HasSubstr("'0.1.5' is not a number"));
}

TEST(WorldIoTest, WallWithOnePointIsAnError) {
  const Result<World> world = ParseWorld(WithLine(4, "  - [[0, 0]]"), "wall.yaml");
  ASSERT_FALSE(world.ok());
  EXPECT_THAT(world.status().message(),
              HasSubstr("wall.yaml:4: walls[0]: a wall needs at least 2 points, got 1"));
}

TEST(WorldIoTest, ObjectWithoutSizeIsAnError) {
  const Result<World> world =
      ParseWorld(WithLine(8, "  - {class: bucket, x: 5.0, y: 3.5, height: 0.4}"), "size.yaml");
  ASSERT_FALSE(world.ok());
  EXPECT_THAT(world.status().message(), HasSubstr("size.yaml:8: objects[1]: needs a size"));
}

TEST(WorldIoTest, UnknownClassAndClassOnObstacleAreErrors) {
  Result<World> world = ParseWorld(
      WithLine(8, "  - {class: bukket, x: 5.0, y: 3.5, radius: 0.1, height: 0.4}"), "c.yaml");
  ASSERT_FALSE(world.ok());
  EXPECT_THAT(world.status().message(), HasSubstr("c.yaml:8: objects[1].class: 'bukket'"));
  world = ParseWorld(WithLine(10, "  - {class: stool, x: 3.0, y: 2.0, radius: 0.1, height: 1}"),
                     "o.yaml");
  ASSERT_FALSE(world.ok());
  EXPECT_THAT(world.status().message(), HasSubstr("o.yaml:10: obstacles[0].class: unknown key"));
}

TEST(WorldIoTest, OdometryScaleErrorIsReadAndBounded) {
  const Result<World> world =
      ParseWorld(WithLine(16, "  odometry_scale_error: [0.02, -0.01]"), "e.yaml");
  ASSERT_TRUE(world.ok()) << world.status().message();
  EXPECT_DOUBLE_EQ(world->robot.odometry_scale_error.distance, 0.02);
  EXPECT_DOUBLE_EQ(world->robot.odometry_scale_error.turn, -0.01);
  EXPECT_THAT(
      ParseWorld(WithLine(16, "  odometry_scale_error: [0.02, -1.0]"), "e.yaml").status().message(),
      HasSubstr("e.yaml:16: robot.odometry_scale_error: expected [distance, turn] fractions"));
}

TEST(WorldIoTest, BadValuesAreErrors) {
  EXPECT_THAT(ParseWorld(WithLine(12, "  start: [1.0, 1.0]"), "s.yaml").status().message(),
              HasSubstr("s.yaml:12: robot.start"));
  EXPECT_THAT(ParseWorld(WithLine(13, "  radius: -0.2"), "r.yaml").status().message(),
              HasSubstr("r.yaml:13: robot.radius: must be positive"));
  EXPECT_THAT(
      ParseWorld(WithLine(19, "detection: {miss_probability: 1.5}"), "d.yaml").status().message(),
      HasSubstr("d.yaml:19: detection.miss_probability: must lie in"));
  EXPECT_THAT(ParseWorld(WithLine(18, "  frame_rate_hz: 20"), "f.yaml").status().message(),
              HasSubstr("f.yaml:18: robot.frame_rate_hz: frame_rate_hz must not exceed"));
}

TEST(WorldIoTest, UnreadableFileNamesTheFile) {
  const Result<World> world = LoadWorld("/nonexistent/dir/missing_world.yaml");
  ASSERT_FALSE(world.ok());
  EXPECT_THAT(world.status().message(), HasSubstr("missing_world.yaml"));
}

TEST(WorldIoTest, LoadWorldTakesTheNameFromTheFileWhenMissing) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("semchain_named_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = dir / "semchain_named_by_file.yaml";
  std::ofstream(path) << WithLine(1, "# no name");
  const Result<World> world = LoadWorld(path);
  ASSERT_TRUE(world.ok()) << world.status().message();
  EXPECT_EQ(world->name, "semchain_named_by_file");
  std::filesystem::remove_all(dir);
}

TEST(WorldIoTest, ValidateCatchesSolidsThroughWallsAndBlockedRoutes) {
  World world = *ParseWorld(kValid, "tiny.yaml");
  World through_wall = world;
  through_wall.objects[1].footprint.center = {5.9, 3.5};  // radius 0.15 crosses x = 6
  EXPECT_THAT(ValidateWorld(through_wall, "w.yaml").message(),
              HasSubstr("w.yaml: objects[1] at (5.90, 3.50) crosses walls[0]"));
  World blocked = world;
  blocked.obstacles[0].footprint.center = {3.0, 1.0};  // on the first leg of the route
  EXPECT_THAT(ValidateWorld(blocked, "w.yaml").message(),
              HasSubstr("the route from mapping_route[0] to mapping_route[1] passes within"));
  World overlapping = world;
  overlapping.obstacles[0].footprint.center = {5.0, 3.4};
  EXPECT_THAT(ValidateWorld(overlapping, "w.yaml").message(), HasSubstr("overlaps objects[1]"));
}

TEST(WorldIoTest, LoadsWaypointFiles) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("semchain_waypoints_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "semchain_route.txt") << "# x y\n1 1\n2.5, 1\n\n3 2  # last\n";
  std::ofstream(dir / "semchain_route.yaml") << "[[1, 1], [2.5, 1]]\n";
  std::ofstream(dir / "semchain_bad_route.txt") << "1 1\n2 x\n";
  const auto text = LoadWaypoints(dir / "semchain_route.txt");
  ASSERT_TRUE(text.ok()) << text.status().message();
  ASSERT_EQ(text->size(), 3u);
  EXPECT_DOUBLE_EQ((*text)[1].x(), 2.5);
  const auto yaml = LoadWaypoints(dir / "semchain_route.yaml");
  ASSERT_TRUE(yaml.ok()) << yaml.status().message();
  EXPECT_EQ(yaml->size(), 2u);
  EXPECT_THAT(LoadWaypoints(dir / "semchain_bad_route.txt").status().message(),
              HasSubstr("semchain_bad_route.txt:2:"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace semchain::sim

namespace semchain::sim {
namespace {

constexpr char kFurnished[] = R"(walls:
  - [[0, 0], [6, 0], [6, 4], [0, 4], [0, 0]]
shell: {wall_texture: paint, floor_texture: wood, floor_color: [150, 110, 80]}
lighting: {ambient: 0.4, directional: 0.6, direction: [1, 0, -1]}
objects:
  - {class: table, x: 2.0, y: 2.0, width: 1.2, depth: 0.7, height: 0.75}
  - {class: computer, x: 2.0, y: 2.1, width: 0.5, depth: 0.2, height: 0.4, base_height: 0.75}
  - {class: chair, x: 4.0, y: 2.0, width: 0.5, depth: 0.5, height: 0.9, shape: prism}
  - {class: sofa, x: 4.5, y: 3.4, width: 1.6, depth: 0.8, height: 0.8, color: [10, 20, 30], texture: metal}
  - class: stool
    x: 1.0
    y: 3.0
    radius: 0.2
    height: 0.5
    parts:
      - {radius: 0.2, bottom: 0.46, top: 0.5}
      - {radius: 0.03, top: 0.46, texture: metal, color: [90, 90, 90]}
robot:
  start: [1.0, 1.0, 0.0]
  camera: {roll_deg: 3, exposure: 1.2, rgb_noise_std: 2, blur_sigma_px: 0.5}
)";

TEST(WorldIoTest, ObjectsOfTheTenClassesAreBuiltOfParts) {
  const Result<World> world = ParseWorld(kFurnished, "flat.yaml");
  ASSERT_TRUE(world.ok()) << world.status().message();
  const std::vector<Solid>& objects = world->objects;
  EXPECT_EQ(objects[0].shape, ObjectShape::kParts);
  EXPECT_GE(objects[0].parts.size(), 5u);                   // a top and four legs at least
  EXPECT_DOUBLE_EQ(objects[1].parts.front().bottom, 0.75);  // standing on the table
  EXPECT_EQ(objects[2].shape, ObjectShape::kPrism);
  EXPECT_TRUE(objects[2].parts.empty());
  // A fixed colour and finish hold for the main surfaces.
  EXPECT_EQ(objects[3].color, (std::array<std::uint8_t, 3>{10, 20, 30}));
  EXPECT_EQ(objects[3].texture, TextureFamily::kMetal);
  // Explicit parts, placed in the world frame.
  ASSERT_EQ(objects[4].parts.size(), 2u);
  EXPECT_EQ(objects[4].parts[1].footprint.shape, Footprint::Shape::kCircle);
  EXPECT_TRUE(objects[4].parts[1].footprint.center.isApprox(Eigen::Vector2d(1.0, 3.0)));
  EXPECT_DOUBLE_EQ(objects[4].parts[1].top, 0.46);
  EXPECT_EQ(objects[4].parts[1].texture, TextureFamily::kMetal);
  EXPECT_TRUE(world->lighting.enabled);
  EXPECT_TRUE(world->shell.textured_floor);
  EXPECT_EQ(world->shell.wall_texture, TextureFamily::kPaint);
  EXPECT_DOUBLE_EQ(world->robot.camera.roll_deg, 3.0);
  EXPECT_DOUBLE_EQ(world->robot.camera.exposure, 1.2);
  // The computer stands on the table: their footprints overlap, their heights do not.
  EXPECT_TRUE(ValidateWorld(*world, "flat.yaml").ok());
  // Two instances of a class differ unless the world fixes their look.
  const Result<World> again = ParseWorld(kFurnished, "flat.yaml");
  EXPECT_EQ(again->objects[0].color, objects[0].color);
}

TEST(WorldIoTest, BadShapesTexturesAndPartsAreErrors) {
  const auto error = [](const std::string& yaml) {
    const Result<World> world = ParseWorld(yaml, "w.yaml");
    return world.ok() ? std::string() : world.status().message();
  };
  std::string yaml = kFurnished;
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string text = yaml;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  EXPECT_EQ(error(with("shape: prism", "shape: blob")),
            "w.yaml:8: objects[2].shape: 'blob' is not a shape (parts, prism)");
  EXPECT_EQ(error(with("texture: metal}", "texture: velvet}")),
            "w.yaml:9: objects[3].texture: 'velvet' is not a texture (pattern, wood, fabric, "
            "metal, plastic, paint)");
  EXPECT_EQ(error(with("{radius: 0.03, top: 0.46", "{x: 0.25, radius: 0.03, top: 0.46")),
            "w.yaml:17: objects[4].parts[1]: lies outside the object's footprint");
  EXPECT_EQ(
      error(with("{radius: 0.2, bottom: 0.46, top: 0.5}", "{radius: 0.2, bottom: 0.46, top: 0.6}")),
      "w.yaml:16: objects[4].parts[0]: needs 0 <= bottom < top <= the object's height "
      "(0.5)");
  EXPECT_EQ(error(with("lighting: {ambient: 0.4,", "lighting: {ambiant: 0.4,")).substr(0, 30),
            "w.yaml:4: lighting.ambiant: un");
}

}  // namespace
}  // namespace semchain::sim
