// The objects and obstacles of a world file, their parts and looks, and the shell's and the
// light's keys.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "core/angles.h"
#include "io/yaml_reader.h"
#include "sim/object_shapes.h"
#include "sim/prism_silhouette.h"
#include "sim/scene.h"
#include "sim/world.h"
#include "sim/world_io_internal.h"

namespace semchain::sim::internal {
namespace {

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

// node[key], an RGB colour of integers in 0..255.
Status ParseColor(const Node& node, const std::string& key, std::array<std::uint8_t, 3>* color) {
  const Result<Node> value = node.Get(key);
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

Status ParseTexture(const Node& node, const std::string& key, TextureFamily* texture) {
  const Result<Node> value = node.Get(key);
  const Result<std::string> name = value->AsString();
  if (!name.ok()) return name.status();
  static const std::vector<std::pair<std::string, TextureFamily>> kNames = {
      {"pattern", TextureFamily::kPattern}, {"wood", TextureFamily::kWood},
      {"fabric", TextureFamily::kFabric},   {"metal", TextureFamily::kMetal},
      {"plastic", TextureFamily::kPlastic}, {"paint", TextureFamily::kPaint}};
  for (const auto& [text, family] : kNames) {
    if (*name == text) {
      *texture = family;
      return Status::Ok();
    }
  }
  return value->Error("'" + *name +
                      "' is not a texture (pattern, wood, fabric, metal, plastic, paint)");
}

Status ParseShape(const Node& node, const std::string& key, ObjectShape* shape) {
  const Result<Node> value = node.Get(key);
  const Result<std::string> name = value->AsString();
  if (!name.ok()) return name.status();
  if (*name != "parts" && *name != "prism") {
    return value->Error("'" + *name + "' is not a shape (parts, prism)");
  }
  *shape = *name == "parts" ? ObjectShape::kParts : ObjectShape::kPrism;
  return Status::Ok();
}

// True when 'inner' lies within 'outer' (a small tolerance for rounding in the file).
bool FootprintInside(const Footprint& inner, const Footprint& outer) {
  constexpr double kTolerance = 1e-6;
  Footprint grown = outer;
  grown.width += 2.0 * kTolerance, grown.depth += 2.0 * kTolerance, grown.radius += kTolerance;
  for (const Eigen::Vector2d& p : FootprintOutline(inner)) {
    if (!FootprintContains(grown, p)) return false;
  }
  return true;
}

// One part of an explicit 'parts' list: x and y in the object's frame (along its yaw, across
// it), heights from the object's base.
Status ParsePart(const Node& node, const Solid& solid, std::size_t index, Part* part) {
  SEMCHAIN_RETURN_IF_ERROR(node.CheckKeys(
      {"x", "y", "width", "depth", "radius", "bottom", "top", "profile", "color", "texture"}));
  double x = 0.0, y = 0.0, bottom = 0.0, top = solid.height;
  SEMCHAIN_RETURN_IF_ERROR(ReadOptional(node, "x", &x));
  SEMCHAIN_RETURN_IF_ERROR(ReadOptional(node, "y", &y));
  Footprint size;
  SEMCHAIN_RETURN_IF_ERROR(ParseSize(node, &size));
  SEMCHAIN_RETURN_IF_ERROR(ReadNonNegative(node, "bottom", &bottom));
  SEMCHAIN_RETURN_IF_ERROR(ReadPositive(node, "top", &top, false));
  if (top <= bottom || top > solid.height + 1e-9) {
    char height[32];
    std::snprintf(height, sizeof(height), "%g", solid.height);
    return node.Error("needs 0 <= bottom < top <= the object's height (" + std::string(height) +
                      ")");
  }
  *part = PlacePart(solid, x, y, size.width, size.depth, size.radius, bottom, top);
  if (!FootprintInside(part->footprint, solid.footprint)) {
    return node.Error("lies outside the object's footprint");
  }
  if (node.Has("profile")) {
    const Result<std::string> profile = node.Get("profile")->AsString();
    if (!profile.ok()) return profile.status();
    if (*profile != "prism" && *profile != "disc") {
      return node.Get("profile")->Error("'" + *profile + "' is not a profile (prism, disc)");
    }
    if (*profile == "disc" && size.shape != Footprint::Shape::kBox) {
      return node.Get("profile")->Error("a disc needs width (its diameter) and depth, not radius");
    }
    part->profile = *profile == "disc" ? Part::Profile::kDisc : Part::Profile::kPrism;
  }
  part->color = solid.color;
  part->texture = solid.texture == TextureFamily::kPattern ? TextureFamily::kPaint : solid.texture;
  if (node.Has("color")) SEMCHAIN_RETURN_IF_ERROR(ParseColor(node, "color", &part->color));
  if (node.Has("texture")) SEMCHAIN_RETURN_IF_ERROR(ParseTexture(node, "texture", &part->texture));
  part->texture_seed = solid.texture_seed * 31u + static_cast<std::uint32_t>(index) + 1u;
  return Status::Ok();
}

Status ParseParts(const Node& node, Solid* solid) {
  const Result<Node> list = node.Get("parts");
  if (!list->IsSequence() || list->size() == 0) return list->Error("expected a list of parts");
  for (std::size_t i = 0; i < list->size(); ++i) {
    Part part;
    SEMCHAIN_RETURN_IF_ERROR(ParsePart(list->At(i), *solid, i, &part));
    solid->parts.push_back(part);
  }
  return Status::Ok();
}

// One semantic object (classes non-empty) or obstacle (classes empty).
Status ParseSolid(const Node& node, const World& world, bool semantic, Solid* solid) {
  std::vector<std::string> keys = {
      "x",     "y",     "yaw",         "width",        "depth",   "radius", "height",
      "color", "plain", "base_height", "texture_seed", "texture", "shape",  "parts"};
  if (semantic) keys.push_back("class");
  SEMCHAIN_RETURN_IF_ERROR(node.CheckKeys(keys));
  if (semantic) {
    Result<Node> name = node.Get("class");
    if (!name.ok()) return name.status();
    Result<std::string> text = name->AsString();
    if (!text.ok()) return text.status();
    if (std::find(world.classes.begin(), world.classes.end(), *text) == world.classes.end()) {
      return name->Error("'" + *text + "' is not in classes (" + JoinNames(world.classes) + ")");
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
  SEMCHAIN_RETURN_IF_ERROR(ReadOptional(node, "plain", &solid->plain));
  if (node.Has("texture_seed")) {
    int seed = 0;
    SEMCHAIN_RETURN_IF_ERROR(ReadNonNegativeInt(node, "texture_seed", &seed));
    solid->texture_seed = static_cast<std::uint32_t>(seed);
  }
  // Objects of the ten classes are built of parts (unless told otherwise), in their class's
  // colours and finish unless the file fixes them; anything else stays one prism.
  solid->shape = semantic && (HasClassShape(solid->class_name) || node.Has("parts"))
                     ? world.object_shapes
                     : ObjectShape::kPrism;
  if (node.Has("shape")) {
    if (!semantic) return node.Get("shape")->Error("only semantic objects have a shape");
    SEMCHAIN_RETURN_IF_ERROR(ParseShape(node, "shape", &solid->shape));
  }
  if (solid->shape == ObjectShape::kParts) {
    const ClassLook look = DrawClassLook(solid->class_name, solid->texture_seed);
    solid->color = look.color;
    solid->texture = look.texture;
  }
  if (node.Has("color")) SEMCHAIN_RETURN_IF_ERROR(ParseColor(node, "color", &solid->color));
  if (node.Has("texture")) SEMCHAIN_RETURN_IF_ERROR(ParseTexture(node, "texture", &solid->texture));
  if (node.Has("parts")) {
    if (solid->shape != ObjectShape::kParts) {
      return node.Get("parts")->Error("an object with shape: prism has no parts");
    }
    return ParseParts(node, solid);
  }
  if (solid->shape == ObjectShape::kParts) {
    solid->parts = BuildClassParts(*solid);
    if (solid->parts.empty()) {
      return node.Error("class '" + solid->class_name +
                        "' has no built-in shape: give its parts or shape: prism");
    }
  }
  return Status::Ok();
}

Status ParseLighting(const Node& node, LightingSpec* lighting) {
  SEMCHAIN_RETURN_IF_ERROR(node.CheckKeys({"ambient", "directional", "direction"}));
  lighting->enabled = true;
  SEMCHAIN_RETURN_IF_ERROR(ReadInRange(node, "ambient", 0.0, 2.0, &lighting->ambient));
  SEMCHAIN_RETURN_IF_ERROR(ReadInRange(node, "directional", 0.0, 2.0, &lighting->directional));
  if (!node.Has("direction")) return Status::Ok();
  const Result<Node> direction = node.Get("direction");
  const Result<std::vector<double>> values = direction->AsDoubleList(3);
  if (!values.ok()) return values.status();
  lighting->direction = Eigen::Vector3d((*values)[0], (*values)[1], (*values)[2]);
  if (lighting->direction.norm() < 1e-9) return direction->Error("must not be zero");
  return Status::Ok();
}

Status ParseShell(const Node& node, ShellLookSpec* shell) {
  SEMCHAIN_RETURN_IF_ERROR(node.CheckKeys({"wall_texture", "floor_color", "floor_texture"}));
  if (node.Has("wall_texture")) {
    SEMCHAIN_RETURN_IF_ERROR(ParseTexture(node, "wall_texture", &shell->wall_texture));
  }
  if (node.Has("floor_texture")) {
    shell->textured_floor = true;
    SEMCHAIN_RETURN_IF_ERROR(ParseTexture(node, "floor_texture", &shell->floor_texture));
  }
  if (node.Has("floor_color")) {
    shell->textured_floor = true;
    SEMCHAIN_RETURN_IF_ERROR(ParseColor(node, "floor_color", &shell->floor_color));
  }
  return Status::Ok();
}

}  // namespace

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
    SEMCHAIN_RETURN_IF_ERROR(ParseSolid(list->At(i), world, semantic, &solid));
    solids->push_back(solid);
  }
  return Status::Ok();
}

Status ParseShellAndLighting(const Node& root, World* world) {
  if (root.Has("object_shapes")) {
    SEMCHAIN_RETURN_IF_ERROR(ParseShape(root, "object_shapes", &world->object_shapes));
  }
  if (root.Has("shell")) SEMCHAIN_RETURN_IF_ERROR(ParseShell(*root.Get("shell"), &world->shell));
  if (root.Has("lighting")) {
    SEMCHAIN_RETURN_IF_ERROR(ParseLighting(*root.Get("lighting"), &world->lighting));
  }
  return Status::Ok();
}

}  // namespace semchain::sim::internal
