#pragma once

#include <opencv2/core.hpp>

#include "core/pose2.h"
#include "sensors/camera.h"
#include "sim/scene.h"

// The 2.5D RGB-D renderer (DESIGN.md §3.1): one ray cast per image column through the world's
// prisms; each surface carries a seeded procedural texture; floor and ceiling are plain.
namespace semchain::sim {

struct RenderOptions {
  bool textured = true;  // false draws flat colours (for debugging)
};

struct RgbdImage {
  cv::Mat rgb;    // CV_8UC3, RGB order
  cv::Mat depth;  // CV_16UC1, millimetres along the optical axis; 0 = no measurement
  // Per pixel: the object index (World::objects) seen there, or -1 (CV_32SC1). The detection
  // model uses it for visibility; it is never written to disk.
  cv::Mat object_ids;
};

// The camera of a robot described by 'spec', with its mounting on the robot.
MountedCamera MakeMountedCamera(const CameraSpec& spec);

// Renders what 'camera' on a robot at 'robot_pose' sees in 'scene'. Deterministic: the same
// inputs give the same bytes.
RgbdImage RenderRgbd(const Scene& scene, const MountedCamera& camera, const Pose2& robot_pose,
                     const RenderOptions& options = {});

}  // namespace semchain::sim
