#include "core/pose2.h"

#include <cmath>
#include <ostream>

#include "core/angles.h"

namespace semchain {

Pose2::Pose2(double x_in, double y_in, double theta_in)
    : x(x_in), y(y_in), theta(NormalizeAngle(theta_in)) {}

Pose2 Pose2::operator*(const Pose2& other) const {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  return Pose2(x + c * other.x - s * other.y, y + s * other.x + c * other.y, theta + other.theta);
}

Eigen::Vector2d Pose2::operator*(const Eigen::Vector2d& point) const {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  return {x + c * point.x() - s * point.y(), y + s * point.x() + c * point.y()};
}

Eigen::Isometry2d Pose2::ToIsometry() const {
  Eigen::Isometry2d transform = Eigen::Isometry2d::Identity();
  transform.linear() = Eigen::Rotation2Dd(theta).toRotationMatrix();
  transform.translation() = translation();
  return transform;
}

Pose2 Pose2::Inverse() const {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  return Pose2(-c * x - s * y, s * x - c * y, -theta);
}

Pose2 Pose2::Between(const Pose2& to) const { return Inverse() * to; }

Pose2 Interpolate(const Pose2& a, const Pose2& b, double t) {
  return Pose2(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y),
               a.theta + t * AngleDifference(b.theta, a.theta));
}

std::ostream& operator<<(std::ostream& os, const Pose2& pose) {
  return os << "(" << pose.x << ", " << pose.y << ", " << pose.theta << ")";
}

}  // namespace semchain
