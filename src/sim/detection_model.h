#pragma once

#include <string>
#include <vector>

#include "core/pose2.h"
#include "core/rng.h"
#include "sensors/camera.h"
#include "sensors/detection.h"
#include "sim/rgbd_renderer.h"
#include "sim/scene.h"

// The simulator's detector: detections made from the truth with an error model
// (World::detection): only objects visible in the rendered frame, inside the field of view and
// range; boxes from their visible pixels; class confusion, misses and false positives; the
// depth of the visible surface, as a depth camera measures it.
namespace semchain::sim {

std::vector<Detection> DetectObjects(const Scene& scene, const MountedCamera& camera,
                                     const Pose2& robot_pose, const RgbdImage& image, Rng& rng);

}  // namespace semchain::sim
