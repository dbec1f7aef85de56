#pragma once

#include <cstdint>
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
//
// Boxes are [x1, y1, x2, y2] in pixel-edge coordinates, as a network's detector reports them:
// pixel (u, v) spans [u, u + 1) × [v, v + 1), so a box covering pixels 10..19 is [10, 20).
namespace semchain::sim {

// How much of an object a frame shows.
struct ObjectVisibility {
  int pixels = 0;    // pixels where the renderer shows the object
  int measured = 0;  // of those, pixels with a depth reading (within the camera's range)
  int u_min = 0, v_min = 0, u_max = -1, v_max = -1;  // bounds of those pixels (inclusive)
  double silhouette = 0.0;  // pixels its whole prism covers inside the image when nothing hides it
  std::vector<std::uint16_t> depths_mm;  // the measured depths of its pixels
  double VisibleFraction() const { return silhouette > 0.0 ? pixels / silhouette : 0.0; }
};

// The visibility of every object of 'world' in 'image', its silhouette the unoccluded pixels
// the renderer counted (RenderOptions::count_unoccluded; 0 when not counted).
std::vector<ObjectVisibility> MeasureVisibility(const RgbdImage& image, const World& world);

// The visibility of every object of 'scene' in 'image', rendered from 'robot_pose'; an entry
// per World::objects index. A prism's silhouette is its projected outline, an object of parts'
// the unoccluded pixels the renderer counted.
std::vector<ObjectVisibility> MeasureVisibility(const Scene& scene, const MountedCamera& camera,
                                                const Pose2& robot_pose, const RgbdImage& image);

// The detections a detector with World::detection's error model reports for 'image', rendered
// by 'camera' on a robot at 'robot_pose'. An object is detected when at least
// min_visible_fraction of its unoccluded silhouette inside the image shows (occlusion hides an
// object, the image border only truncates its box), its box spans min_box_pixels both ways,
// and most of its pixels have a depth reading (it is within the camera's range); then it may be
// missed or confused. Its depth_m is the median depth of its visible pixels (plus noise), never its
// hidden centre. Poisson false positives land on background pixels with the depth there. Class ids
// index World::classes (DefaultClassNames() when empty). Draws from 'rng' only.
std::vector<Detection> DetectObjects(const Scene& scene, const MountedCamera& camera,
                                     const Pose2& robot_pose, const RgbdImage& image, Rng& rng);

}  // namespace semchain::sim
