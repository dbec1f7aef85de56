#include "sim/furnished_room.h"

#include "core/angles.h"

namespace semchain::sim {
namespace {

Solid MakeBox(const std::string& class_name, double x, double y, double yaw, double width,
              double depth, double height, std::array<std::uint8_t, 3> color, std::uint32_t seed) {
  Solid solid;
  solid.class_name = class_name;
  solid.footprint.shape = Footprint::Shape::kBox;
  solid.footprint.center = {x, y};
  solid.footprint.yaw = yaw;
  solid.footprint.width = width;
  solid.footprint.depth = depth;
  solid.height = height;
  solid.color = color;
  solid.texture_seed = seed;
  return solid;
}

Solid MakeCylinder(const std::string& class_name, double x, double y, double radius, double height,
                   std::array<std::uint8_t, 3> color, std::uint32_t seed) {
  Solid solid;
  solid.class_name = class_name;
  solid.footprint.shape = Footprint::Shape::kCircle;
  solid.footprint.center = {x, y};
  solid.footprint.radius = radius;
  solid.height = height;
  solid.color = color;
  solid.texture_seed = seed;
  return solid;
}

}  // namespace

World FurnishedRoomWorld() {
  World world;
  world.name = "furnished_room";
  world.seed = 7;
  world.walls = {{{0, 0}, {8, 0}, {8, 6}, {0, 6}, {0, 0}}};
  world.wall_height = 2.5;
  world.objects = {
      MakeBox("door", 6.5, 0.05, 0.0, 0.9, 0.1, 2.0, {150, 100, 60}, 11),
      MakeBox("cabinet", 7.7, 3.5, kPi / 2.0, 1.0, 0.5, 1.2, {90, 110, 160}, 12),
      MakeCylinder("bucket", 6.0, 4.8, 0.15, 0.4, {200, 60, 50}, 13),
      MakeBox("chair", 5.2, 1.5, 0.4, 0.5, 0.5, 0.9, {70, 140, 80}, 14),
      MakeCylinder("stool", 4.5, 4.2, 0.2, 0.45, {180, 160, 60}, 15),
  };
  world.obstacles = {
      MakeCylinder("", 4.0, 2.2, 0.15, 2.5, {235, 235, 235}, 21),
      MakeBox("", 6.2, 3.0, 0.0, 0.4, 0.4, 0.15, {120, 120, 130}, 22),
  };
  world.classes = {"door", "cabinet", "bucket", "chair", "stool"};
  world.robot.start = Pose2(2.0, 3.0, 0.0);
  world.mapping_route = {{1, 1}, {7, 1}, {7, 5}, {1, 5}, {1, 1}};
  world.trial_region = {{1, 1}, {3.5, 1}, {3.5, 5}, {1, 5}};
  return world;
}

}  // namespace semchain::sim
