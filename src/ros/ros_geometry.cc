#include "ros/ros_geometry.h"

#include <algorithm>
#include <cmath>

namespace semchain::ros1 {
namespace {

// q and -q are the same rotation; w >= 0 is the one people expect to read in a bag.
geometry_msgs::Quaternion ToQuaternionMsg(const Eigen::Quaterniond& q) {
  const double sign = q.w() < 0.0 ? -1.0 : 1.0;
  geometry_msgs::Quaternion msg;
  msg.x = sign * q.x();
  msg.y = sign * q.y();
  msg.z = sign * q.z();
  msg.w = sign * q.w();
  return msg;
}

// A rotation about z by 'yaw', written directly so that a heading of 0 gives exactly (0, 0, 0, 1).
Eigen::Quaterniond YawQuaternion(double yaw) {
  return Eigen::Quaterniond(std::cos(0.5 * yaw), 0.0, 0.0, std::sin(0.5 * yaw));
}

Eigen::Quaterniond FromQuaternionMsg(const geometry_msgs::Quaternion& q) {
  return Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized();
}

// A Pose and a Transform are the same thing under other field names.
geometry_msgs::Pose AsPose(const geometry_msgs::Transform& transform) {
  geometry_msgs::Pose pose;
  pose.position.x = transform.translation.x;
  pose.position.y = transform.translation.y;
  pose.position.z = transform.translation.z;
  pose.orientation = transform.rotation;
  return pose;
}

geometry_msgs::Transform AsTransform(const geometry_msgs::Pose& pose) {
  geometry_msgs::Transform transform;
  transform.translation.x = pose.position.x;
  transform.translation.y = pose.position.y;
  transform.translation.z = pose.position.z;
  transform.rotation = pose.orientation;
  return transform;
}

}  // namespace

geometry_msgs::Transform ToTransformMsg(const Pose2& pose) {
  geometry_msgs::Transform msg;
  msg.translation.x = pose.x;
  msg.translation.y = pose.y;
  msg.translation.z = 0.0;
  msg.rotation = ToQuaternionMsg(YawQuaternion(pose.theta));
  return msg;
}

geometry_msgs::Transform ToTransformMsg(const Eigen::Isometry3d& pose) {
  geometry_msgs::Transform msg;
  msg.translation.x = pose.translation().x();
  msg.translation.y = pose.translation().y();
  msg.translation.z = pose.translation().z();
  msg.rotation = ToQuaternionMsg(Eigen::Quaterniond(pose.rotation()));
  return msg;
}

geometry_msgs::Pose ToPoseMsg(const Pose2& pose) { return AsPose(ToTransformMsg(pose)); }

Eigen::Isometry3d ToIsometry(const geometry_msgs::Transform& transform) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = FromQuaternionMsg(transform.rotation).toRotationMatrix();
  pose.translation() =
      Eigen::Vector3d(transform.translation.x, transform.translation.y, transform.translation.z);
  return pose;
}

Eigen::Isometry3d ToIsometry(const geometry_msgs::Pose& pose) {
  return ToIsometry(AsTransform(pose));
}

Pose2 PlanarPose(const Eigen::Isometry3d& pose) {
  const Eigen::Matrix3d r = pose.rotation();
  return Pose2(pose.translation().x(), pose.translation().y(), std::atan2(r(1, 0), r(0, 0)));
}

double TiltRadians(const Eigen::Isometry3d& pose) {
  return std::acos(std::clamp(pose.rotation()(2, 2), -1.0, 1.0));
}

}  // namespace semchain::ros1
