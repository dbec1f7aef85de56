#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/pose2.h"

// The chain camera → robot → world → grid of seed 000, eq. 2–5.
namespace semchain {

// The camera's optical frame (z forward, x right, y down) placed on the robot (x forward,
// y left, z up): position (x, y, z) in metres, yaw about the robot's z axis and pitch downwards
// (positive looks at the floor) and roll about the viewing direction (positive turns the
// image clockwise as the camera sees it), all in radians.
Eigen::Isometry3d RobotFromOpticalCamera(double x, double y, double z, double yaw, double pitch,
                                         double roll = 0.0);

// Eq. 2: [X_r Y_r Z_r 1]ᵀ = [R_cr T_cr; 0 1] [X_c Y_c Z_c 1]ᵀ.
Eigen::Vector3d CameraToRobot(const Eigen::Isometry3d& robot_from_camera,
                              const Eigen::Vector3d& point_camera);

// Eq. 4: R_wr is the rotation by θ_t about z, T_wr = (x_t, y_t, 0)ᵀ.
Eigen::Isometry3d WorldFromRobot(const Pose2& robot_pose);

// Eq. 3: [X_w Y_w Z_w 1]ᵀ = [R_wr T_wr; 0 1] [X_r Y_r Z_r 1]ᵀ.
Eigen::Vector3d RobotToWorld(const Pose2& robot_pose, const Eigen::Vector3d& point_robot);

// Eq. 5: the grid cell (X_g, Y_g) of a world point for a map of 'resolution' metres per cell
// whose cell (0, 0) has its lower-left corner at 'origin'. The paper rounds X_w / r; we take
// the floor relative to the origin, which is the map_server convention: the cell that
// contains the point.
Eigen::Vector2i WorldToGrid(const Eigen::Vector2d& point_world, double resolution,
                            const Eigen::Vector2d& origin = Eigen::Vector2d::Zero());

// The centre of grid cell 'cell', the inverse of WorldToGrid up to half a cell.
Eigen::Vector2d GridToWorld(const Eigen::Vector2i& cell, double resolution,
                            const Eigen::Vector2d& origin = Eigen::Vector2d::Zero());

}  // namespace semchain
