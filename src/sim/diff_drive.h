#pragma once

#include <Eigen/Core>

#include "core/pose2.h"

// A differential-drive (unicycle) robot: its kinematics and a point-to-point controller.
namespace semchain::sim {

struct VelocityCommand {
  double linear = 0.0;   // m/s, along the heading
  double angular = 0.0;  // rad/s, counter-clockwise
};

// The pose after driving 'command' for 'dt' seconds from 'pose': exact integration along the
// circular arc (a straight line when angular is zero).
Pose2 IntegrateDiffDrive(const Pose2& pose, const VelocityCommand& command, double dt);

// Limits and gains of the controller; the simulator takes the limits from RobotSpec.
struct DriveOptions {
  double max_speed = 0.5;          // m/s
  double max_turn_rate = 1.0;      // rad/s
  double min_speed = 0.05;         // m/s, the slowest approach so a goal is always reached
  double slowdown_distance = 0.3;  // metres: within it the speed falls linearly towards the goal
  // Heading errors above this make the robot turn in place before it drives (radians, about
  // 11°), so that it leaves a waypoint along the next leg instead of swinging wide.
  double turn_in_place_angle = 0.2;
  double heading_gain = 2.0;     // 1/s: turn rate per radian of heading error
  double goal_tolerance = 0.02;  // metres: a goal closer than this is reached
};

// Drives towards one point: turns in place while the goal is far off the heading, otherwise
// drives with a bounded speed that shrinks near the goal and steers proportionally to the
// heading error. Never reverses.
class PointController {
 public:
  explicit PointController(const DriveOptions& options) : options_(options) {}

  // The command from 'pose' towards 'goal'; zero when the goal is within goal_tolerance.
  // 'dt' bounds the step so that the robot does not overshoot the goal or its heading.
  VelocityCommand Command(const Pose2& pose, const Eigen::Vector2d& goal, double dt) const;
  bool Reached(const Pose2& pose, const Eigen::Vector2d& goal) const;

  const DriveOptions& options() const { return options_; }

 private:
  DriveOptions options_;
};

// Rotates towards 'target_heading' at up to max_turn_rate without overshooting within 'dt'.
VelocityCommand TurnTowards(const Pose2& pose, double target_heading, const DriveOptions& options,
                            double dt);

}  // namespace semchain::sim
