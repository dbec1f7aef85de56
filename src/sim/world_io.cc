// Parsing of world files (DESIGN.md §5.2): one function per section, each checking its keys so
// that a misspelt key is an error naming its path, never a silently ignored setting.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/angles.h"
#include "io/yaml_reader.h"
#include "sensors/detection.h"
#include "sim/world.h"
#include "sim/world_io_internal.h"

namespace semchain::sim {
namespace {

using internal::ParsePointList;
using internal::ReadNonNegative;
using internal::ReadNonNegativeInt;
using internal::ReadPositive;
using yaml::Node;
using yaml::ReadOptional;

Status ParseWalls(const Node& root, World* world) {
  Result<Node> walls = root.Get("walls");
  if (!walls.ok()) return walls.status();
  if (!walls->IsSequence() || walls->size() == 0) {
    return walls->Error("expected a list of wall polylines, each a list of [x, y] points");
  }
  for (std::size_t i = 0; i < walls->size(); ++i) {
    std::vector<Eigen::Vector2d> line;
    SEMCHAIN_RETURN_IF_ERROR(ParsePointList(walls->At(i), 2, "a wall", &line));
    world->walls.push_back(std::move(line));
  }
  SEMCHAIN_RETURN_IF_ERROR(ReadPositive(root, "wall_height", &world->wall_height, false));
  return ReadNonNegative(root, "wall_thickness", &world->wall_thickness);
}

Status ParseClasses(const Node& root, World* world) {
  world->classes = DefaultClassNames();
  if (!root.Has("classes")) return Status::Ok();
  Result<Node> list = root.Get("classes");
  if (!list->IsSequence() || list->size() == 0) return list->Error("expected a list of names");
  world->classes.clear();
  for (std::size_t i = 0; i < list->size(); ++i) {
    Result<std::string> name = list->At(i).AsString();
    if (!name.ok()) return name.status();
    if (name->empty() ||
        std::find(world->classes.begin(), world->classes.end(), *name) != world->classes.end()) {
      return list->At(i).Error("class names must be non-empty and unique");
    }
    world->classes.push_back(*name);
  }
  return Status::Ok();
}

Status ParseRoutes(const Node& root, World* world) {
  if (root.Has("mapping_route")) {
    SEMCHAIN_RETURN_IF_ERROR(
        ParsePointList(*root.Get("mapping_route"), 1, "a route", &world->mapping_route));
  }
  if (root.Has("trial_region")) {
    SEMCHAIN_RETURN_IF_ERROR(
        ParsePointList(*root.Get("trial_region"), 3, "a region", &world->trial_region));
  }
  return Status::Ok();
}

Result<World> ParseRoot(const Node& root) {
  if (!root.IsMap()) return root.Error("expected a map with walls, objects, robot, ...");
  SEMCHAIN_RETURN_IF_ERROR(
      root.CheckKeys({"name", "seed", "classes", "walls", "wall_height", "wall_thickness",
                      "object_shapes", "objects", "obstacles", "robot", "detection",
                      "mapping_route", "trial_region", "lighting", "shell"}));
  World world;
  SEMCHAIN_RETURN_IF_ERROR(ReadOptional(root, "name", &world.name));
  if (root.Has("seed")) {
    int seed = 0;
    SEMCHAIN_RETURN_IF_ERROR(ReadNonNegativeInt(root, "seed", &seed));
    world.seed = static_cast<std::uint32_t>(seed);
  }
  SEMCHAIN_RETURN_IF_ERROR(ParseClasses(root, &world));
  SEMCHAIN_RETURN_IF_ERROR(ParseWalls(root, &world));
  SEMCHAIN_RETURN_IF_ERROR(internal::ParseShellAndLighting(root, &world));
  SEMCHAIN_RETURN_IF_ERROR(internal::ParseSolids(root, "objects", world, &world.objects));
  SEMCHAIN_RETURN_IF_ERROR(internal::ParseSolids(root, "obstacles", world, &world.obstacles));
  Result<Node> robot = root.Get("robot");
  if (!robot.ok()) return robot.status();
  SEMCHAIN_RETURN_IF_ERROR(internal::ParseRobot(*robot, &world.robot));
  if (root.Has("detection")) {
    SEMCHAIN_RETURN_IF_ERROR(
        internal::ParseDetectionModel(*root.Get("detection"), &world.detection));
  }
  SEMCHAIN_RETURN_IF_ERROR(ParseRoutes(root, &world));
  return world;
}

}  // namespace

Result<World> ParseWorld(const std::string& yaml_text, const std::string& source_name) {
  Result<Node> root = Node::LoadString(yaml_text, source_name);
  if (!root.ok()) return root.status();
  Result<World> world = ParseRoot(*root);
  if (world.ok() && world->name.empty()) {
    world->name = std::filesystem::path(source_name).stem().string();
  }
  return world;
}

Result<World> LoadWorld(const std::filesystem::path& path) {
  Result<Node> root = Node::LoadFile(path);
  if (!root.ok()) return root.status();
  Result<World> world = ParseRoot(*root);
  if (world.ok() && world->name.empty()) world->name = path.stem().string();
  return world;
}

}  // namespace semchain::sim
