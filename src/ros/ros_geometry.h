#pragma once

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Transform.h>

#include <Eigen/Geometry>

#include "core/pose2.h"

// Poses between semchain (Pose2 on the floor plane, Eigen isometries) and geometry_msgs.
namespace semchain::ros1 {

geometry_msgs::Transform ToTransformMsg(const Pose2& pose);
geometry_msgs::Transform ToTransformMsg(const Eigen::Isometry3d& pose);
geometry_msgs::Pose ToPoseMsg(const Pose2& pose);

Eigen::Isometry3d ToIsometry(const geometry_msgs::Transform& transform);
Eigen::Isometry3d ToIsometry(const geometry_msgs::Pose& pose);

// The pose on the floor plane: x, y and the heading of the x axis, dropping z, roll and pitch.
Pose2 PlanarPose(const Eigen::Isometry3d& pose);

// The angle between the z axes of 'pose' and its parent: how far a frame leans out of the
// plane (0 for a level laser, π for one mounted upside down).
double TiltRadians(const Eigen::Isometry3d& pose);

}  // namespace semchain::ros1
