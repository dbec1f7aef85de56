#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <vector>

#include "core/pose2.h"
#include "semantic/semantic_options.h"
#include "sensors/camera.h"
#include "sensors/detection.h"

// From a detection and the aligned depth image to points on the map (seed 000 eq. 2–5): each
// pixel of the box's core with a depth near the detection's is back-projected into the camera
// frame, moved to the robot frame (eq. 2) and to the world by the robot's SLAM pose (eq. 3–4).
namespace semchain::semantic {

// The world points (x, y, z; z up from the floor) of 'detection' seen in 'depth_m' (CV_32FC1,
// metres along the optical axis, 0 = none) by 'camera' on a robot at 'robot_pose'.
// 'class_extent' (metres) sets the depth gate around the detection's depth.
std::vector<Eigen::Vector3d> DetectionWorldPoints(const Detection& detection,
                                                  const cv::Mat& depth_m,
                                                  const MountedCamera& camera,
                                                  const Pose2& robot_pose, double class_extent,
                                                  const DetectionPointOptions& options);

// What one image column saw, on the floor plane: free space from the camera to just before
// the nearest surface, and that surface.
struct FreeRay {
  int column = 0;
  Eigen::Vector2d from;     // the camera
  Eigen::Vector2d to;       // end of the free space ('from' when the surface is very near)
  Eigen::Vector2d surface;  // the nearest surface point
};

// One ray per sampled image column whose pixels saw a surface between the height limits.
std::vector<FreeRay> FreeSpaceRays(const cv::Mat& depth_m, const MountedCamera& camera,
                                   const Pose2& robot_pose, const FreeSpaceOptions& options);

// 'ray' (in the robot frame) seen from 'robot_pose': FreeSpaceRays(..., robot_pose, ...) is
// FreeSpaceRays(..., Pose2(), ...) moved by this, to the last bit, so that evidence kept in
// the robot frame can be re-posed when SLAM corrects the trajectory.
FreeRay PoseRay(const FreeRay& ray, const Pose2& robot_pose);
// The same for a point of DetectionWorldPoints (its x and y).
Eigen::Vector2d PosePoint(const Eigen::Vector2d& point, const Pose2& robot_pose);

}  // namespace semchain::semantic
