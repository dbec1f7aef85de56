#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/pose2.h"
#include "sensors/camera.h"
#include "sim/world.h"

// Where a solid would appear in an image if nothing hid it: the projection of its whole prism.
// The detection model compares it with the pixels the renderer actually shows of the solid.
namespace semchain::sim {

// The footprint's outline, counter-clockwise: a box's four corners, or 'circle_sides' points
// on a circle.
std::vector<Eigen::Vector2d> FootprintOutline(const Footprint& footprint, int circle_sides = 32);

// The convex outline in pixel coordinates of the prism of 'solid' seen by 'camera' on a robot at
// 'robot_pose', cut at a near plane 1 cm in front of the camera (not at the image border); empty
// when the whole prism is behind that plane.
std::vector<Eigen::Vector2d> ProjectPrism(const Solid& solid, const MountedCamera& camera,
                                          const Pose2& robot_pose);

// The area in pixels of the part of convex 'polygon' inside a width × height image, whose
// pixel (u, v) covers [u - 0.5, u + 0.5] × [v - 0.5, v + 0.5].
double AreaInsideImage(const std::vector<Eigen::Vector2d>& polygon, int width, int height);

}  // namespace semchain::sim
