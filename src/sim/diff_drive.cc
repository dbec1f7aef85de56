#include "sim/diff_drive.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"

namespace semchain::sim {

Pose2 IntegrateDiffDrive(const Pose2& pose, const VelocityCommand& command, double dt) {
  const double dtheta = command.angular * dt;
  double forward = command.linear * dt;  // displacement along the chord's own frame
  double sideways = 0.0;
  if (std::abs(dtheta) > 1e-9) {
    // Arc of radius v/ω: the chord ends at (R sin Δθ, R (1 - cos Δθ)) in the start frame.
    const double radius = command.linear / command.angular;
    forward = radius * std::sin(dtheta);
    sideways = radius * (1.0 - std::cos(dtheta));
  }
  return pose * Pose2(forward, sideways, dtheta);
}

VelocityCommand TurnTowards(const Pose2& pose, double target_heading, const DriveOptions& options,
                            double dt) {
  const double error = AngleDifference(target_heading, pose.theta);
  // The largest rate that does not overshoot within one step, bounded by the robot's limit.
  const double rate = std::min(options.max_turn_rate, std::abs(error) / dt);
  return {0.0, std::copysign(rate, error)};
}

bool PointController::Reached(const Pose2& pose, const Eigen::Vector2d& goal) const {
  return (goal - pose.translation()).norm() < options_.goal_tolerance;
}

VelocityCommand PointController::Command(const Pose2& pose, const Eigen::Vector2d& goal,
                                         double dt) const {
  const Eigen::Vector2d delta = goal - pose.translation();
  const double distance = delta.norm();
  if (distance < options_.goal_tolerance) return {};
  const double bearing = std::atan2(delta.y(), delta.x());
  const double error = AngleDifference(bearing, pose.theta);
  if (std::abs(error) > options_.turn_in_place_angle)
    return TurnTowards(pose, bearing, options_, dt);
  VelocityCommand command;
  const double ramp = std::min(1.0, distance / options_.slowdown_distance);
  command.linear = std::max(options_.min_speed, options_.max_speed * ramp);
  // Never drive past the goal within one step, and slow down while the heading is off.
  command.linear = std::min(command.linear, distance / dt) * std::cos(error);
  command.angular =
      std::clamp(options_.heading_gain * error, -options_.max_turn_rate, options_.max_turn_rate);
  return command;
}

}  // namespace semchain::sim
