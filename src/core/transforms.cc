#include "core/transforms.h"

#include <cmath>

namespace semchain {

Eigen::Isometry3d RobotFromOpticalCamera(double x, double y, double z, double yaw, double pitch,
                                         double roll) {
  // Columns: the optical axes expressed in a forward-looking robot frame.
  Eigen::Matrix3d robot_from_optical;
  robot_from_optical << 0, 0, 1,  //
      -1, 0, 0,                   //
      0, -1, 0;
  const Eigen::Matrix3d mount = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                                 Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                                 Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                                    .toRotationMatrix();
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() = mount * robot_from_optical;
  transform.translation() = Eigen::Vector3d(x, y, z);
  return transform;
}

Eigen::Vector3d CameraToRobot(const Eigen::Isometry3d& robot_from_camera,
                              const Eigen::Vector3d& point_camera) {
  return robot_from_camera * point_camera;
}

Eigen::Isometry3d WorldFromRobot(const Pose2& robot_pose) {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() = Eigen::AngleAxisd(robot_pose.theta, Eigen::Vector3d::UnitZ()).matrix();
  transform.translation() = Eigen::Vector3d(robot_pose.x, robot_pose.y, 0.0);
  return transform;
}

Eigen::Vector3d RobotToWorld(const Pose2& robot_pose, const Eigen::Vector3d& point_robot) {
  return WorldFromRobot(robot_pose) * point_robot;
}

Eigen::Vector2i WorldToGrid(const Eigen::Vector2d& point_world, double resolution,
                            const Eigen::Vector2d& origin) {
  const Eigen::Vector2d scaled = (point_world - origin) / resolution;
  return {static_cast<int>(std::floor(scaled.x())), static_cast<int>(std::floor(scaled.y()))};
}

Eigen::Vector2d GridToWorld(const Eigen::Vector2i& cell, double resolution,
                            const Eigen::Vector2d& origin) {
  return origin + (cell.cast<double>() + Eigen::Vector2d::Constant(0.5)) * resolution;
}

}  // namespace semchain
