#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <iosfwd>

namespace semchain {

// A rigid transform of the plane, SE(2): rotation by 'theta' then translation by (x, y).
// As a robot pose it maps points from the robot frame into the world frame.
struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;  // radians, kept in (-pi, pi] by every operation below.

  Pose2() = default;
  Pose2(double x_in, double y_in, double theta_in);

  Eigen::Vector2d translation() const { return {x, y}; }

  // this ⊕ other: 'other' expressed in this frame, returned in the parent frame.
  Pose2 operator*(const Pose2& other) const;
  // Maps a point from this frame into the parent frame.
  Eigen::Vector2d operator*(const Eigen::Vector2d& point) const;
  // The same transform with its rotation evaluated once, for mapping many points by one pose
  // (operator* above evaluates cos and sin for every point).
  Eigen::Isometry2d ToIsometry() const;
  Pose2 Inverse() const;
  // The pose of 'to' in the frame of this pose: this⁻¹ ⊕ to (the ⊖ of Lu & Milios).
  Pose2 Between(const Pose2& to) const;
};

// Interpolates between 'a' (t = 0) and 'b' (t = 1): translation linearly, heading on the
// shorter arc. t outside [0, 1] extrapolates.
Pose2 Interpolate(const Pose2& a, const Pose2& b, double t);

std::ostream& operator<<(std::ostream& os, const Pose2& pose);

}  // namespace semchain
