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

using internal::JoinNames;
using internal::ParsePointList;
using internal::ReadNonNegative;
using internal::ReadNonNegativeInt;
using internal::ReadPositive;
using internal::ReadRequired;
using yaml::Node;
using yaml::ReadOptional;

// A texture seed for solid 'index' of a kind, spread over 32 bits (splitmix64 finaliser) so
// that neighbouring indices and world seeds give unrelated textures.
std::uint32_t DeriveTextureSeed(std::uint32_t world_seed, int kind, std::size_t index) {
  std::uint64_t z = (static_cast<std::uint64_t>(world_seed) << 32) ^
                    (static_cast<std::uint64_t>(kind) << 24) ^ index;
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return static_cast<std::uint32_t>((z ^ (z >> 31)) & 0xffffffffULL);
}

Status ParseSize(const Node& node, Footprint* footprint) {
  const bool circle = node.Has("radius");
  const bool box = node.Has("width") || node.Has("depth");
  if (circle == box) {
    return node.Error(circle ? "give either radius (a circle) or width and depth (a box), not both"
                             : "needs a size: radius (a circle) or width and depth (a box)");
  }
  if (circle) {
    footprint->shape = Footprint::Shape::kCircle;
    return ReadPositive(node, "radius", &footprint->radius, /*required=*/true);
  }
  footprint->shape = Footprint::Shape::kBox;
  SEMCHAIN_RETURN_IF_ERROR(ReadPositive(node, "width", &footprint->width, true));
  return ReadPositive(node, "depth", &footprint->depth, true);
}

Status ParseColor(const Node& node, std::array<std::uint8_t, 3>* color) {
  if (!node.Has("color")) return Status::Ok();
  const Result<Node> value = node.Get("color");
  const Result<std::vector<double>> rgb = value->AsDoubleList(3);
  if (!rgb.ok()) return rgb.status();
  for (int i = 0; i < 3; ++i) {
    const double c = (*rgb)[i];
    if (c < 0.0 || c > 255.0 || c != std::floor(c)) {
      return value->Error("colour components are integers in 0..255");
    }
    (*color)[i] = static_cast<std::uint8_t>(c);
  }
  return Status::Ok();
}

// One semantic object (classes non-empty) or obstacle (classes empty).
Status ParseSolid(const Node& node, const std::vector<std::string>& classes, Solid* solid) {
  const bool semantic = !classes.empty();
  std::vector<std::string> keys = {"x",      "y",      "yaw",   "width",       "depth",
                                   "radius", "height", "color", "base_height", "texture_seed",
                                   "plain"};
  if (semantic) keys.push_back("class");
  SEMCHAIN_RETURN_IF_ERROR(node.CheckKeys(keys));
  if (semantic) {
    Result<Node> name = node.Get("class");
    if (!name.ok()) return name.status();
    Result<std::string> text = name->AsString();
    if (!text.ok()) return text.status();
    if (std::find(classes.begin(), classes.end(), *text) == classes.end()) {
      return name->Error("'" + *text + "' is not in classes (" + JoinNames(classes) + ")");
    }
    solid->class_name = *text;
  }
  Footprint& footprint = solid->footprint;
  SEMCHAIN_RETURN_IF_ERROR(ReadRequired(node, "x", &footprint.center.x()));
  SEMCHAIN_RETURN_IF_ERROR(ReadRequired(node, "y", &footprint.center.y()));
  SEMCHAIN_RETURN_IF_ERROR(ReadOptional(node, "yaw", &footprint.yaw));
  footprint.yaw = NormalizeAngle(footprint.yaw);
  SEMCHAIN_RETURN_IF_ERROR(ParseSize(node, &footprint));
  SEMCHAIN_RETURN_IF_ERROR(ReadPositive(node, "height", &solid->height, true));
  SEMCHAIN_RETURN_IF_ERROR(ReadNonNegative(node, "base_height", &solid->base_height));
  SEMCHAIN_RETURN_IF_ERROR(ParseColor(node, &solid->color));
  if (node.Has("plain")) {
    const Result<Node> plain = node.Get("plain");
    if (!plain.ok()) return plain.status();
    const Result<bool> value = plain->AsBool();
    if (!value.ok()) return value.status();
    solid->plain = *value;
  }
  if (node.Has("texture_seed")) {
    int seed = 0;
    SEMCHAIN_RETURN_IF_ERROR(ReadNonNegativeInt(node, "texture_seed", &seed));
    solid->texture_seed = static_cast<std::uint32_t>(seed);
  }
  return Status::Ok();
}

Status ParseSolids(const Node& root, const std::string& key, const World& world,
                   std::vector<Solid>* solids) {
  if (!root.Has(key)) return Status::Ok();
  Result<Node> list = root.Get(key);
  if (!list.ok()) return list.status();
  if (list->IsNull()) return Status::Ok();
  if (!list->IsSequence()) return list->Error("expected a list of solids");
  const bool semantic = key == "objects";
  for (std::size_t i = 0; i < list->size(); ++i) {
    Solid solid;
    solid.texture_seed = DeriveTextureSeed(world.seed, semantic ? 1 : 2, i);
    const std::vector<std::string> no_classes;
    SEMCHAIN_RETURN_IF_ERROR(
        ParseSolid(list->At(i), semantic ? world.classes : no_classes, &solid));
    solids->push_back(solid);
  }
  return Status::Ok();
}

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
  SEMCHAIN_RETURN_IF_ERROR(root.CheckKeys({"name", "seed", "classes", "walls", "wall_height",
                                           "wall_thickness", "objects", "obstacles", "robot",
                                           "detection", "mapping_route", "trial_region"}));
  World world;
  SEMCHAIN_RETURN_IF_ERROR(ReadOptional(root, "name", &world.name));
  if (root.Has("seed")) {
    int seed = 0;
    SEMCHAIN_RETURN_IF_ERROR(ReadNonNegativeInt(root, "seed", &seed));
    world.seed = static_cast<std::uint32_t>(seed);
  }
  SEMCHAIN_RETURN_IF_ERROR(ParseClasses(root, &world));
  SEMCHAIN_RETURN_IF_ERROR(ParseWalls(root, &world));
  SEMCHAIN_RETURN_IF_ERROR(ParseSolids(root, "objects", world, &world.objects));
  SEMCHAIN_RETURN_IF_ERROR(ParseSolids(root, "obstacles", world, &world.obstacles));
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
