#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "core/pose2.h"
#include "core/status.h"
#include "sim/odometry_model.h"

// The simulated world (DESIGN.md §3.1, format §5.2).
namespace semchain::sim {

// A 2D footprint: a box (width along its yaw direction, depth across it) or a circle.
struct Footprint {
  enum class Shape { kBox, kCircle };
  Shape shape = Shape::kBox;
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double yaw = 0.0;     // radians, counter-clockwise from the world x axis
  double width = 0.0;   // box: extent along yaw (metres)
  double depth = 0.0;   // box: extent across yaw (metres)
  double radius = 0.0;  // circle
};

// The surface finish of a solid or part, which picks its procedural texture (texture.h).
// kPattern is the bold patterns every surface had before the object classes got their looks
// (bricks, tiles, blobs, posters): the bundled worlds' figures were measured with it.
enum class TextureFamily { kPattern, kWood, kFabric, kMetal, kPlastic, kPaint };

// How a semantic object is built: one prism over its whole footprint, or the parts of its
// class's characteristic shape (object_shapes.h: a table is a top on four legs).
enum class ObjectShape { kPrism, kParts };

// One convex piece of an object (a table's top, one of its legs), in world coordinates: a
// prism between two heights, or a vertical disc (a clock's face) standing in a thin box
// footprint whose width is the disc's diameter, centred between 'bottom' and 'top'.
struct Part {
  enum class Profile { kPrism, kDisc };
  Profile profile = Profile::kPrism;
  Footprint footprint;
  double bottom = 0.0;  // metres above the floor
  double top = 0.0;
  std::array<std::uint8_t, 3> color = {200, 200, 200};
  TextureFamily texture = TextureFamily::kPaint;
  std::uint32_t texture_seed = 0;
};

// A vertical prism standing on the floor: a semantic object or a plain obstacle.
struct Solid {
  std::string class_name;  // empty for a non-semantic obstacle
  Footprint footprint;
  double height = 1.0;             // metres
  double base_height = 0.0;        // metres above the floor where it starts (e.g. a table top)
  std::uint32_t texture_seed = 0;  // derived from the world seed and index when not given
  std::array<std::uint8_t, 3> color = {200, 200, 200};  // base colour (RGB) of its texture
  // Rendered in its flat colour without a texture pattern (e.g. the coloured test boxes a
  // detector test model recognises).
  bool plain = false;
  TextureFamily texture = TextureFamily::kPattern;
  ObjectShape shape = ObjectShape::kPrism;
  // The pieces it is built of when shape is kParts (from the class's shape builder or the world
  // file), each inside the footprint and between base_height and base_height + height.
  std::vector<Part> parts;
};

// A box solid of 'class_name' (empty for an obstacle) centred at (x, y), axis-aligned:
// 'width' along x, 'depth' along y, 'height' above the floor.
inline Solid MakeBoxSolid(std::string class_name, double x, double y, double width, double depth,
                          double height) {
  Solid solid;
  solid.class_name = std::move(class_name);
  solid.footprint.center = {x, y};
  solid.footprint.width = width;
  solid.footprint.depth = depth;
  solid.height = height;
  return solid;
}

struct LidarSpec {
  double height = 0.19;  // metres above the floor (the scan plane)
  int beams = 360;
  double fov_deg = 360.0;       // centred on the robot's heading
  double max_range = 12.0;      // metres
  double noise_std = 0.01;      // metres, Gaussian range noise
  double forward_offset = 0.0;  // metres ahead of the robot centre
};

struct CameraSpec {
  double height = 0.5;    // metres above the floor
  double fov_deg = 60.0;  // horizontal
  int width = 320;
  int height_px = 240;
  double max_range = 6.0;  // metres
  double pitch_deg = 0.0;  // positive looks down
  double forward_offset = 0.0;
  double depth_noise_std = 0.0;  // metres, per-pixel Gaussian noise on the depth image
  double roll_deg = 0.0;         // positive turns the image clockwise as the camera sees it
  double exposure = 1.0;         // gain on the rendered colours (1: as shaded)
  double rgb_noise_std = 0.0;    // per-pixel Gaussian noise on each colour channel (0..255)
  double blur_sigma_px = 0.0;    // Gaussian blur of the colour image (0: sharp)
};

// Light on the scene. Without it (enabled false) a face is shaded by how squarely the camera
// sees it, as every world was before lighting existed (the bundled figures were measured so).
struct LightingSpec {
  bool enabled = false;
  double ambient = 0.45;  // fraction of a surface's colour lit from everywhere
  double directional = 0.55;
  Eigen::Vector3d direction = Eigen::Vector3d(0.4, 0.3, -1.0);  // the light travels along it
};

// The look of the room's shell. kPattern walls and a plain grey floor are the defaults of the
// bundled worlds.
struct ShellLookSpec {
  TextureFamily wall_texture = TextureFamily::kPattern;
  bool textured_floor = false;
  std::array<std::uint8_t, 3> floor_color = {118, 118, 118};
  TextureFamily floor_texture = TextureFamily::kWood;
};

// The detection error model (DESIGN.md §3.1).
struct DetectionModelSpec {
  double miss_probability = 0.05;           // a visible object is not reported
  double confusion_probability = 0.02;      // reported with another class
  double false_positives_per_frame = 0.02;  // Poisson mean of spurious boxes
  double min_visible_fraction = 0.3;        // of the object's projected box that must be seen
  int min_box_pixels = 12;                  // smaller boxes are not detected
  double box_noise_px = 2.0;                // std of box edge jitter
  double depth_noise_std = 0.02;            // metres
};

struct RobotSpec {
  Pose2 start;
  double radius = 0.2;  // metres, for the controller's clearance
  LidarSpec lidar;
  CameraSpec camera;
  // Thrun's odometry model α1..α4 (Probabilistic Robotics, table 5.6).
  std::array<double, 4> odometry_noise = {0.05, 0.05, 0.05, 0.05};
  // Systematic odometry error, as a real robot's wrong wheel radius and wheel base give: the
  // odometry reads every translation (1 + distance) times and every rotation (1 + turn) times
  // its true size before the noise above. 0 = unbiased (the bundled worlds before the campus).
  OdometryScaleError odometry_scale_error;
  double max_speed = 0.5;      // m/s
  double max_turn_rate = 1.0;  // rad/s
  double scan_rate_hz = 10.0;  // lidar and odometry records per second
  double frame_rate_hz = 2.0;  // camera frames per second
};

struct World {
  std::string name;
  // Seeds the surfaces' procedural textures (a solid without its own texture_seed gets one
  // derived from this and its index), so two worlds that differ only here look different.
  std::uint32_t seed = 0;
  std::vector<std::vector<Eigen::Vector2d>> walls;  // polylines
  double wall_height = 2.5;
  double wall_thickness = 0.0;  // 0 = infinitely thin segments
  ShellLookSpec shell;
  LightingSpec lighting;
  // How objects of the ten classes are built when the object does not say (key object_shapes).
  ObjectShape object_shapes = ObjectShape::kParts;
  std::vector<Solid> objects;    // semantic objects (class_name set)
  std::vector<Solid> obstacles;  // non-semantic
  RobotSpec robot;
  DetectionModelSpec detection;
  std::vector<std::string> classes;  // class-id order; default DefaultClassNames()
  std::vector<Eigen::Vector2d> mapping_route;
  std::vector<Eigen::Vector2d> trial_region;  // polygon
};

// True when some semantic object of 'world' is built of parts (ObjectShape::kParts).
inline bool HasObjectParts(const World& world) {
  for (const Solid& solid : world.objects) {
    if (solid.shape == ObjectShape::kParts && !solid.parts.empty()) return true;
  }
  return false;
}

// Loads a world (src/sim/world_io.cc); unknown keys, malformed numbers, a wall with fewer than two
// points, … are errors naming the file, line and key path ("w.yaml:7: objects[2].radius: not a
// number").
Result<World> LoadWorld(const std::filesystem::path& path);
Result<World> ParseWorld(const std::string& yaml_text, const std::string& source_name);

}  // namespace semchain::sim
