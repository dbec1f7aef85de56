#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace semchain {

// A pinhole camera without distortion; pixel (u, v) has its centre at integer coordinates
// (OpenCV's convention), u to the right, v down.
struct PinholeCamera {
  int width = 320;
  int height = 240;
  double fx = 277.0;
  double fy = 277.0;
  double cx = 159.5;
  double cy = 119.5;

  // A camera of 'width' × 'height' pixels with square pixels and horizontal field of view
  // 'horizontal_fov_radians', principal point at the image centre.
  static PinholeCamera FromFov(int width, int height, double horizontal_fov_radians);

  // Pixel of a point in the optical frame (z forward); undefined for z <= 0.
  Eigen::Vector2d Project(const Eigen::Vector3d& point_camera) const;
  // The point at depth 'z' (along the optical axis, metres) seen at pixel (u, v).
  Eigen::Vector3d Backproject(double u, double v, double z) const;
  bool Contains(double u, double v) const {
    return u >= -0.5 && v >= -0.5 && u < width - 0.5 && v < height - 0.5;
  }
};

// A camera with its mounting on the robot.
struct MountedCamera {
  PinholeCamera intrinsics;
  Eigen::Isometry3d robot_from_camera = Eigen::Isometry3d::Identity();
  double max_range = 6.0;  // metres; depth beyond it reads 0 (no measurement)
};

}  // namespace semchain
