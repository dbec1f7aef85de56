#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "core/status.h"
#include "sim/world.h"

// Reading worlds and routes (DESIGN.md §5.2); LoadWorld / ParseWorld are declared in world.h.
// Geometry that parses but makes no sense (an object through a wall, a route through a cabinet)
// is caught by ValidateWorld, which names the offending key path.
//
// Keys (metres, radians unless the name says _deg or _hz; defaults are those of world.h):
//   name (default: the file's stem), seed (textures), classes (class-id order),
//   walls (required: polylines of ≥ 2 [x, y] points), wall_height, wall_thickness,
//   objects / obstacles: lists of {class (objects only), x, y, yaw, radius | width + depth,
//     height, base_height, color: [r, g, b], texture_seed, plain (flat colour: true/false)},
//   robot (required): {start: [x, y, theta] (required), radius, odometry_noise: [α1..α4],
//     odometry_scale_error: [distance, turn] (systematic over-reading fractions),
//     max_speed, max_turn_rate, scan_rate_hz, frame_rate_hz (≤ scan_rate_hz),
//     lidar: {height, beams, fov_deg, max_range, noise_std, forward_offset},
//     camera: {height, fov_deg, width, height_px, max_range, pitch_deg, forward_offset,
//              depth_noise_std}},
//   detection: {miss_probability, confusion_probability, false_positives_per_frame,
//               min_visible_fraction, min_box_pixels, box_noise_px, depth_noise_std},
//   mapping_route: [[x, y], ...], trial_region: [[x, y], ...] (≥ 3 corners).
namespace semchain::sim {

// Checks what parsing cannot: every solid lies inside the walls' bounding box and, except
// doors (which sit in the wall line by design), crosses no wall; the start pose and every
// mapping-route segment keep 'clearance' metres from every surface (robot.radius when
// negative); the trial region has at least three corners. 'source_name' prefixes errors.
Status ValidateWorld(const World& world, const std::string& source_name, double clearance = -1.0);

// Reads a list of waypoints: a YAML sequence of [x, y] pairs, or a text file with one "x y"
// (or "x, y") per line where '#' starts a comment. Errors name the file and line.
Result<std::vector<Eigen::Vector2d>> LoadWaypoints(const std::filesystem::path& path);

}  // namespace semchain::sim
