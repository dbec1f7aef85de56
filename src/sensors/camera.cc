#include "sensors/camera.h"

#include <cmath>

namespace semchain {

PinholeCamera PinholeCamera::FromFov(int width_in, int height_in, double horizontal_fov_radians) {
  PinholeCamera camera;
  camera.width = width_in;
  camera.height = height_in;
  camera.fx = 0.5 * width_in / std::tan(0.5 * horizontal_fov_radians);
  camera.fy = camera.fx;
  camera.cx = 0.5 * (width_in - 1);
  camera.cy = 0.5 * (height_in - 1);
  return camera;
}

Eigen::Vector2d PinholeCamera::Project(const Eigen::Vector3d& p) const {
  return {fx * p.x() / p.z() + cx, fy * p.y() / p.z() + cy};
}

Eigen::Vector3d PinholeCamera::Backproject(double u, double v, double z) const {
  return {(u - cx) * z / fx, (v - cy) * z / fy, z};
}

}  // namespace semchain
