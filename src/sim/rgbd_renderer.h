#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "core/pose2.h"
#include "sensors/camera.h"
#include "sim/scene.h"

// The 2.5D RGB-D renderer (DESIGN.md §3.1). Walls and solids are prisms standing on the floor;
// one horizontal ray cast (Scene::CastAll) per image column lists every prism it passes, and
// each pixel's 3D ray then meets the first one whose vertical extent (or top face) it reaches,
// or else the floor or the ceiling. Walls and solids carry seeded procedural textures
// (sim/texture.h); the ceiling is plain, the floor plain or textured (World::shell). Faces are
// shaded by the world's light (World::lighting) or, without one, by how squarely they are seen.
namespace semchain::sim {

struct RenderOptions {
  bool textured = true;  // false draws each surface in its flat base colour (debugging)
  // Per-pixel Gaussian noise on the depth image, metres (CameraSpec::depth_noise_std).
  double depth_noise_std_meters = 0.0;
  // Seeds the depth noise. The caller varies it per frame (e.g. from the run seed and the frame
  // index); the same seed and inputs give the same bytes.
  std::uint64_t noise_seed = 0;
  // Surfaces farther than this (horizontally) are not drawn; the depth image stops at the
  // camera's max_range anyway, the colour image looks as far as this.
  double far_clip_meters = 200.0;
  // The camera's colour pipeline (CameraSpec): a gain, per-channel Gaussian noise (0..255
  // scale, seeded by noise_seed) and a Gaussian blur; the defaults leave the image as shaded.
  double exposure = 1.0;
  double rgb_noise_std = 0.0;
  double blur_sigma_px = 0.0;
  // Also count, per object, the pixels that would show it if nothing else stood in the way
  // (RgbdImage::unoccluded_pixels): how much of it a frame hides, for objects built of parts
  // whose silhouette is no convex outline.
  bool count_unoccluded = false;
};

struct RgbdImage {
  cv::Mat rgb;    // CV_8UC3, RGB order (convert to BGR before cv::imwrite)
  cv::Mat depth;  // CV_16UC1, millimetres along the optical axis; 0 = no measurement
  // Per pixel: the object index (World::objects) seen there, or -1 (CV_32SC1). The detection
  // model uses it for visibility; it is never written to disk.
  cv::Mat object_ids;
  // With RenderOptions::count_unoccluded, per World::objects index: the pixels whose ray meets
  // the object, whatever is in front of it.
  std::vector<int> unoccluded_pixels;
};

// The camera of a robot described by 'spec': intrinsics from its horizontal field of view and
// size, mounted 'forward_offset' ahead of the robot centre at 'height', pitched down by
// 'pitch_deg', looking along the robot's heading.
MountedCamera MakeMountedCamera(const CameraSpec& spec);

// Options that render a camera described by 'spec' with its depth noise, seeded 'noise_seed'.
RenderOptions MakeRenderOptions(const CameraSpec& spec, std::uint64_t noise_seed);

// Renders what 'camera' on a robot at 'robot_pose' sees in 'scene': colour, depth (0 beyond
// camera.max_range and on the ceiling, whose height is World::wall_height) and object ids.
// Deterministic: the same inputs give the same bytes.
RgbdImage RenderRgbd(const Scene& scene, const MountedCamera& camera, const Pose2& robot_pose,
                     const RenderOptions& options = {});

}  // namespace semchain::sim
