#include "sim/random_room.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/angles.h"
#include "core/rng.h"
#include "sensors/detection.h"
#include "sim/object_shapes.h"
#include "sim/prism_silhouette.h"
#include "sim/scene.h"

namespace semchain::sim {
namespace {

using Polygon = std::vector<Eigen::Vector2d>;

double Uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}
int UniformInt(Rng& rng, int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }
bool Chance(Rng& rng, double p) { return Uniform(rng, 0.0, 1.0) < p; }

// True when convex polygons p and q overlap (no separating axis among their edge normals).
bool ConvexOverlap(const Polygon& p, const Polygon& q) {
  for (const Polygon* shape : {&p, &q}) {
    for (std::size_t i = 0; i < shape->size(); ++i) {
      const Eigen::Vector2d edge = (*shape)[(i + 1) % shape->size()] - (*shape)[i];
      const Eigen::Vector2d axis(-edge.y(), edge.x());
      double p_lo = 1e300, p_hi = -1e300, q_lo = 1e300, q_hi = -1e300;
      for (const auto& v : p)
        p_lo = std::min(p_lo, v.dot(axis)), p_hi = std::max(p_hi, v.dot(axis));
      for (const auto& v : q)
        q_lo = std::min(q_lo, v.dot(axis)), q_hi = std::max(q_hi, v.dot(axis));
      if (p_hi < q_lo || q_hi < p_lo) return false;
    }
  }
  return true;
}

Footprint Grown(Footprint f, double margin) {
  f.width += 2.0 * margin, f.depth += 2.0 * margin, f.radius += margin;
  return f;
}

// The room being furnished: its size, what stands in it and where nothing may go.
class Furnisher {
 public:
  Furnisher(World& world, Rng& rng, double width, double depth, double borrowed_footprint_fraction)
      : world_(world),
        rng_(rng),
        width_(width),
        depth_(depth),
        borrowed_footprint_fraction_(borrowed_footprint_fraction) {}

  // Adds a partition wall from one side part-way across the room (more occlusion).
  void MaybePartition() {
    if (!Chance(rng_, 0.3)) return;
    const bool vertical = Chance(rng_, 0.5);
    const double along = vertical ? width_ : depth_, across = vertical ? depth_ : width_;
    const double at = Uniform(rng_, 0.35, 0.65) * along;
    const double reach = Uniform(rng_, 0.3, 0.5) * across;
    const bool from_low = Chance(rng_, 0.5);
    Eigen::Vector2d a, b;
    if (vertical) {
      a = {at, from_low ? 0.0 : depth_}, b = {at, from_low ? reach : depth_ - reach};
    } else {
      a = {from_low ? 0.0 : width_, at}, b = {from_low ? reach : width_ - reach, at};
    }
    world_.walls.push_back({a, b});
    Footprint keep_out;
    keep_out.center = 0.5 * (a + b);
    keep_out.yaw = std::atan2((b - a).y(), (b - a).x());
    keep_out.width = (b - a).norm();
    keep_out.depth = 0.02;
    taken_.push_back(FootprintOutline(Grown(keep_out, 0.05)));
  }

  // Tries to stand an object of 'class_name' somewhere it fits; returns its index or -1.
  int Place(const std::string& class_name) {
    const ClassSizeRange range = SizeRangeOf(class_name);
    const ClassSizeRange footprint_range = FootprintRange(class_name);
    for (int attempt = 0; attempt < 60; ++attempt) {
      Solid solid;
      solid.class_name = class_name;
      solid.shape = ObjectShape::kParts;
      solid.texture_seed = static_cast<std::uint32_t>(rng_());
      const bool round = range.round || (class_name == "stool" && Chance(rng_, 0.5));
      const double w = Uniform(rng_, footprint_range.width_min, footprint_range.width_max);
      const double d = Uniform(rng_, footprint_range.depth_min, footprint_range.depth_max);
      solid.height = Uniform(rng_, range.height_min, range.height_max);
      solid.base_height = Uniform(rng_, range.base_min, range.base_max);
      if (round) {
        solid.footprint.shape = Footprint::Shape::kCircle;
        solid.footprint.radius = 0.5 * std::min(w, d);
      } else {
        solid.footprint.width = w;
        solid.footprint.depth = d;
      }
      if (class_name == "clock") solid.height = w;  // a disc
      if (!Position(solid)) continue;
      if (!Fits(solid)) continue;
      const ClassLook look = DrawClassLook(class_name, solid.texture_seed);
      solid.color = look.color;
      solid.texture = look.texture;
      solid.parts = BuildClassParts(solid);
      if (class_name != "door" && class_name != "clock") {
        taken_.push_back(FootprintOutline(Grown(solid.footprint, 0.05)));
      }
      world_.objects.push_back(solid);
      if (class_name == "table") tables_.push_back(static_cast<int>(world_.objects.size()) - 1);
      return static_cast<int>(world_.objects.size()) - 1;
    }
    return -1;
  }

  // A computer on one of the tables (on the floor when there is none).
  void PlaceComputer() {
    if (tables_.empty()) {
      Place("computer");
      return;
    }
    const Solid& table = world_.objects[tables_[UniformInt(rng_, 0, int(tables_.size()) - 1)]];
    world_.objects.push_back(OnTable("computer", SizeRangeOf("computer"), table));
  }

  // A desk clock on one of the tables, clear of what stands there already (on a wall when no
  // table has room).
  void PlaceDeskClock() {
    for (int attempt = 0; attempt < 10 && !tables_.empty(); ++attempt) {
      const Solid& table = world_.objects[tables_[UniformInt(rng_, 0, int(tables_.size()) - 1)]];
      if (table.footprint.width < 0.4) continue;
      Solid clock = OnTable("clock", DeskClockSizeRange(), table);
      const Polygon outline = FootprintOutline(clock.footprint);
      const double top = table.base_height + table.height;
      const bool clear =
          std::none_of(world_.objects.begin(), world_.objects.end(), [&](const Solid& other) {
            return other.base_height >= top - 1e-6 &&
                   ConvexOverlap(outline, FootprintOutline(other.footprint));
          });
      if (!clear) continue;
      world_.objects.push_back(std::move(clock));
      return;
    }
    Place("clock");
  }

  void PlaceDistractor() {
    for (int attempt = 0; attempt < 30; ++attempt) {
      Solid solid;
      solid.texture_seed = static_cast<std::uint32_t>(rng_());
      if (Chance(rng_, 0.5)) {
        solid.footprint.shape = Footprint::Shape::kCircle;
        solid.footprint.radius = Uniform(rng_, 0.05, 0.3);
      } else {
        solid.footprint.width = Uniform(rng_, 0.1, 0.7);
        solid.footprint.depth = Uniform(rng_, 0.1, 0.7);
        solid.footprint.yaw = Uniform(rng_, -kPi, kPi);
      }
      solid.height = Uniform(rng_, 0.1, 1.6);
      solid.footprint.center = {Uniform(rng_, 0.4, width_ - 0.4), Uniform(rng_, 0.4, depth_ - 0.4)};
      for (int c = 0; c < 3; ++c)
        solid.color[c] = static_cast<std::uint8_t>(UniformInt(rng_, 20, 240));
      solid.texture = static_cast<TextureFamily>(UniformInt(rng_, 0, 5));
      if (!Fits(solid)) continue;
      taken_.push_back(FootprintOutline(Grown(solid.footprint, 0.05)));
      world_.obstacles.push_back(solid);
      return;
    }
  }

 private:
  // An object of 'class_name' sized from 'range' standing on 'table', its front towards the
  // table's front or back edge, somewhere along it.
  Solid OnTable(const std::string& class_name, const ClassSizeRange& range, const Solid& table) {
    Solid solid;
    solid.class_name = class_name;
    solid.shape = ObjectShape::kParts;
    solid.texture_seed = static_cast<std::uint32_t>(rng_());
    solid.footprint.width =
        std::min(Uniform(rng_, range.width_min, range.width_max), table.footprint.width - 0.1);
    solid.footprint.depth = Uniform(rng_, range.depth_min, range.depth_max);
    solid.height = Uniform(rng_, range.height_min, range.height_max);
    solid.base_height = table.base_height + table.height;
    const double side = Chance(rng_, 0.5) ? 1.0 : -1.0;
    const double slack =
        std::max(0.0, 0.5 * (table.footprint.width - solid.footprint.width) - 0.05);
    const double x = Uniform(rng_, -slack, slack);
    const double y =
        side * std::max(0.0, 0.5 * table.footprint.depth - 0.5 * solid.footprint.depth - 0.05);
    const double c = std::cos(table.footprint.yaw), s = std::sin(table.footprint.yaw);
    solid.footprint.center = table.footprint.center + Eigen::Vector2d(c * x - s * y, s * x + c * y);
    solid.footprint.yaw = NormalizeAngle(table.footprint.yaw + (side > 0 ? 0.0 : kPi));
    const ClassLook look = DrawClassLook(class_name, solid.texture_seed);
    solid.color = look.color;
    solid.texture = look.texture;
    solid.parts = BuildClassParts(solid);
    return solid;
  }

  // The inward normal and a point of wall 'side' (0 south, 1 east, 2 north, 3 west) at
  // fraction 't' along it.
  std::pair<Eigen::Vector2d, Eigen::Vector2d> WallPoint(int side, double t) const {
    switch (side) {
      case 0:
        return {{t * width_, 0.0}, {0.0, 1.0}};
      case 1:
        return {{width_, t * depth_}, {-1.0, 0.0}};
      case 2:
        return {{t * width_, depth_}, {0.0, -1.0}};
      default:
        return {{0.0, t * depth_}, {1.0, 0.0}};
    }
  }

  // Chooses the solid's position and yaw: in a wall (doors), on a wall (clocks), backed against
  // one (cabinets, sofas, beds, sometimes tables) or free.
  bool Position(Solid& solid) {
    const std::string& name = solid.class_name;
    const bool against = name == "cabinet" || name == "sofa" || name == "bed" || name == "clock" ||
                         name == "door" || (name == "table" && Chance(rng_, 0.3));
    Footprint& f = solid.footprint;
    if (!against) {
      f.center = {Uniform(rng_, 0.3, width_ - 0.3), Uniform(rng_, 0.3, depth_ - 0.3)};
      f.yaw = Uniform(rng_, -kPi, kPi);
      return true;
    }
    const int side = UniformInt(rng_, 0, 3);
    const double length = side % 2 == 0 ? width_ : depth_;
    const double half = 0.5 * (f.shape == Footprint::Shape::kCircle ? 2.0 * f.radius : f.width);
    if (length < 2.0 * half + 0.4) return false;
    const double t = Uniform(rng_, (half + 0.2) / length, 1.0 - (half + 0.2) / length);
    const auto [point, inward] = WallPoint(side, t);
    // The object's back (+y in its frame) towards the wall: across = -inward.
    f.yaw = std::atan2(inward.x(), -inward.y());
    const double depth = f.shape == Footprint::Shape::kCircle ? 2.0 * f.radius : f.depth;
    const double off = name == "door" ? 0.0 : 0.5 * depth + (name == "clock" ? 0.002 : 0.03);
    f.center = point + off * inward;
    return true;
  }

  bool Fits(const Solid& solid) const {
    const Polygon outline = FootprintOutline(solid.footprint);
    if (solid.class_name == "door") {
      // Doors stand in the wall line; keep them off the corners and each other.
      for (const int d : doors_) {
        if ((world_.objects[d].footprint.center - solid.footprint.center).norm() < 1.3)
          return false;
      }
      return true;
    }
    for (const Eigen::Vector2d& p : outline) {
      if (p.x() < 0.001 || p.y() < 0.001 || p.x() > width_ - 0.001 || p.y() > depth_ - 0.001) {
        return false;
      }
    }
    // Nothing in front of a door (0.9 m), so that it stays a door one can walk through.
    for (const Solid& other : world_.objects) {
      if (other.class_name != "door") continue;
      Footprint swing = other.footprint;
      swing.depth = 1.8;
      if (ConvexOverlap(outline, FootprintOutline(swing))) return false;
    }
    if (solid.class_name == "clock") {
      for (const Solid& other : world_.objects) {
        if (other.class_name == "clock" &&
            (other.footprint.center - solid.footprint.center).norm() < 1.0) {
          return false;
        }
      }
      return true;  // above the furniture
    }
    for (const Polygon& taken : taken_) {
      if (ConvexOverlap(outline, taken)) return false;
    }
    return true;
  }

 public:
  void NoteDoor(int index) { doors_.push_back(index); }

 private:
  World& world_;
  // The size range whose width and depth the next object of 'class_name' draws from: its own,
  // or with RandomRoomOptions::borrowed_footprint_fraction a donor's (its height stays its own).
  ClassSizeRange FootprintRange(const std::string& class_name) {
    if (borrowed_footprint_fraction_ <= 0.0) return SizeRangeOf(class_name);
    const std::vector<std::string> donors = FootprintDonors(class_name);
    if (donors.empty() || !Chance(rng_, borrowed_footprint_fraction_)) {
      return SizeRangeOf(class_name);
    }
    return SizeRangeOf(donors[UniformInt(rng_, 0, static_cast<int>(donors.size()) - 1)]);
  }

  Rng& rng_;
  double width_, depth_;
  double borrowed_footprint_fraction_;
  std::vector<Polygon> taken_;
  std::vector<int> tables_;
  std::vector<int> doors_;
};

}  // namespace

ClassSizeRange DeskClockSizeRange() { return {0.25, 0.5, 0.06, 0.2, 0.2, 0.4}; }

std::vector<std::string> FootprintDonors(const std::string& class_name) {
  const std::vector<std::vector<std::string>> groups = {{"bucket", "cabinet", "chair", "stool"},
                                                        {"cabinet", "table", "sofa", "bed"}};
  std::vector<std::string> donors;
  for (const std::vector<std::string>& group : groups) {
    if (std::find(group.begin(), group.end(), class_name) == group.end()) continue;
    for (const std::string& other : group) {
      if (other != class_name) donors.push_back(other);
    }
  }
  return donors;
}

World RandomRoom(std::uint64_t seed, const RandomRoomOptions& options) {
  Rng rng = MakeRng(seed, 0x700d);
  World world;
  world.name = "random_room_" + std::to_string(seed);
  world.seed = static_cast<std::uint32_t>(rng());
  world.classes = DefaultClassNames();
  const double width = Uniform(rng, options.min_size_meters, options.max_size_meters);
  const double depth = Uniform(rng, options.min_size_meters, options.max_size_meters);
  world.walls = {{{0.0, 0.0}, {width, 0.0}, {width, depth}, {0.0, depth}, {0.0, 0.0}}};
  world.wall_height = Uniform(rng, 2.4, 3.0);
  const TextureFamily walls[] = {TextureFamily::kPattern, TextureFamily::kPaint,
                                 TextureFamily::kPaint, TextureFamily::kWood,
                                 TextureFamily::kPlastic};
  world.shell.wall_texture = walls[UniformInt(rng, 0, 4)];
  world.shell.textured_floor = true;
  const TextureFamily floors[] = {TextureFamily::kWood, TextureFamily::kFabric,
                                  TextureFamily::kPlastic, TextureFamily::kPaint};
  world.shell.floor_texture = floors[UniformInt(rng, 0, 3)];
  for (int c = 0; c < 3; ++c)
    world.shell.floor_color[c] = static_cast<std::uint8_t>(UniformInt(rng, 60, 210));
  world.lighting.enabled = true;
  world.lighting.ambient = Uniform(rng, 0.3, 0.6);
  world.lighting.directional = Uniform(rng, 0.3, 0.7);
  const double azimuth = Uniform(rng, -kPi, kPi), elevation = Uniform(rng, 0.4, 1.4);
  world.lighting.direction =
      Eigen::Vector3d(std::cos(azimuth) * std::cos(elevation),
                      std::sin(azimuth) * std::cos(elevation), -std::sin(elevation));
  Furnisher furnisher(world, rng, width, depth, options.borrowed_footprint_fraction);
  furnisher.MaybePartition();
  // Large pieces first, while there is room; then one of every other class; then extras.
  std::vector<std::string> order = {"door",  "bed",   "sofa",  "cabinet", "table",
                                    "clock", "chair", "stool", "bucket"};
  const std::vector<std::string>& classes = DefaultClassNames();
  const int extras = UniformInt(rng, 0, options.extra_objects_max);
  for (int i = 0; i < extras; ++i) {
    const std::string& name = classes[UniformInt(rng, 0, static_cast<int>(classes.size()) - 1)];
    if (name != "computer") order.push_back(name);
  }
  int desk_clocks = 0;
  for (const std::string& name : order) {
    // Drawn only when asked for, so that rooms without desk clocks keep their seeds' draws.
    if (name == "clock" && options.desk_clock_fraction > 0.0 &&
        Chance(rng, options.desk_clock_fraction)) {
      ++desk_clocks;  // after the computers, so that they keep their places on the tables
      continue;
    }
    const int index = furnisher.Place(name);
    if (index >= 0 && name == "door") furnisher.NoteDoor(index);
  }
  furnisher.PlaceComputer();
  if (Chance(rng, 0.3)) furnisher.PlaceComputer();
  for (int i = 0; i < desk_clocks; ++i) furnisher.PlaceDeskClock();
  const int distractors = UniformInt(rng, 0, options.distractors_max);
  for (int i = 0; i < distractors; ++i) furnisher.PlaceDistractor();
  world.object_shapes = ObjectShape::kParts;
  world.robot.start = Pose2(0.5 * width, 0.5 * depth, 0.0);
  return world;
}

std::optional<CameraView> RandomCameraView(const World& world, int target, int width, int height,
                                           std::uint64_t seed) {
  Rng rng = MakeRng(seed, 0xca3);
  const Scene scene(world);
  const Solid& object = world.objects[target];
  const Eigen::Vector2d centre = object.footprint.center;
  // A wall object (door, clock) is seen from the room side: its front.
  const Eigen::Vector2d front(std::sin(object.footprint.yaw), -std::cos(object.footprint.yaw));
  const bool on_wall = object.class_name == "door" || object.class_name == "clock";
  const double object_mid = object.base_height + 0.5 * object.height;
  for (int attempt = 0; attempt < 80; ++attempt) {
    const double distance = Uniform(rng, on_wall && object.class_name == "clock" ? 1.8 : 0.8, 5.0);
    double bearing = Uniform(rng, -kPi, kPi);
    if (on_wall) bearing = std::atan2(front.y(), front.x()) + Uniform(rng, -1.1, 1.1);
    const Eigen::Vector2d at =
        centre + distance * Eigen::Vector2d(std::cos(bearing), std::sin(bearing));
    if (scene.IsOccupied(at, 0.25)) continue;
    // Inside the room (the outer wall is its first polyline).
    if (!PolygonContains(world.walls.front(), at)) continue;
    CameraView view;
    view.camera.width = width;
    view.camera.height_px = height;
    view.camera.fov_deg = Uniform(rng, 55.0, 75.0);
    view.camera.max_range = 8.0;
    view.camera.height = Uniform(rng, 0.3, 1.3);
    const double look = std::atan2((centre - at).y(), (centre - at).x());
    const double heading = NormalizeAngle(look + Uniform(rng, -0.35, 0.35));
    const double down = std::atan2(view.camera.height - object_mid, distance);
    view.camera.pitch_deg = std::clamp(RadToDeg(down) + Uniform(rng, -8.0, 8.0), -35.0, 40.0);
    view.camera.roll_deg = std::clamp(std::normal_distribution<double>(0.0, 3.0)(rng), -8.0, 8.0);
    view.camera.exposure = Uniform(rng, 0.75, 1.3);
    view.camera.rgb_noise_std = Uniform(rng, 0.0, 6.0);
    view.camera.blur_sigma_px = Chance(rng, 0.3) ? Uniform(rng, 0.3, 1.2) : 0.0;
    view.robot_pose = Pose2(at.x(), at.y(), heading);
    return view;
  }
  return std::nullopt;
}

}  // namespace semchain::sim
