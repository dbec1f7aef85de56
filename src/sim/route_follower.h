#pragma once

#include <Eigen/Core>
#include <numbers>
#include <vector>

#include "core/pose2.h"
#include "core/status.h"
#include "sim/diff_drive.h"
#include "sim/scene.h"
#include "sim/world.h"

// Trajectory generation (DESIGN.md §3.1 "Routes"): the true motion of the robot along a
// mapping route (waypoints) or the trial behaviour (rotate in place, then move ahead), sampled
// at the scan rate. Sensors are simulated afterwards along the samples.
namespace semchain::sim {

// What the robot does. kMapping follows World::mapping_route; kWaypoints follows 'waypoints'
// (a route file); kTrial rotates in place and then drives ahead (TrialOptions).
struct RouteSpec {
  enum class Kind { kMapping, kTrial, kWaypoints };
  Kind kind = Kind::kMapping;
  std::vector<Eigen::Vector2d> waypoints;  // kWaypoints only
};

// The trial behaviour of seed 000 §4 ("control the robot to rotate in place"): one full turn
// counter-clockwise, then a short drive straight ahead that stops before anything in the way.
struct TrialOptions {
  double rotation_radians = 2.0 * std::numbers::pi;
  double forward_distance_meters = 1.0;  // at most this far
  // Kept between the robot's outline and the first surface ahead (of any height).
  double stop_clearance_meters = 0.15;
  // A robot that looks for more (active relocalization), off by default: after the turns it
  // faces the heading with the most room ahead (of 36, room counted up to
  // open_look_ahead_meters) before it drives, so that a start in a corner drives out into the
  // room instead of stopping at the wall the turns happened to end facing, ...
  bool face_most_open = false;
  double open_look_ahead_meters = 5.0;
  // ... and turns in place again by this much where the drive ended (0: no second look).
  double rotation_after_radians = 0.0;
};

struct TrajectoryOptions {
  double sample_rate_hz = 10.0;  // one sample per scan (RobotSpec::scan_rate_hz)
  int control_substeps = 5;      // controller updates per sample
  TrialOptions trial;
  // Fail when the robot comes closer than its radius to any surface (a bad route file).
  bool check_collisions = true;
};

// One instant of the true motion.
struct TrajectorySample {
  double time = 0.0;         // seconds since the start
  Pose2 pose;                // world frame
  VelocityCommand velocity;  // the command being executed at that instant
};

// The drive limits of 'robot' with the controller's default gains.
DriveOptions DriveOptionsFor(const RobotSpec& robot);

// The true trajectory of 'robot' starting at 'start' and doing 'route' in 'scene', sampled
// at options.sample_rate_hz from time 0 (the start pose, at rest) until the route is done.
// Errors: an empty route, a waypoint not reached in a generous time budget, or (with
// check_collisions) the robot touching a surface; the message names the waypoint.
Result<std::vector<TrajectorySample>> GenerateTrajectory(const Scene& scene, const RobotSpec& robot,
                                                         const RouteSpec& route, const Pose2& start,
                                                         const TrajectoryOptions& options = {});

// How far the robot at 'pose' can drive straight ahead before its outline (a disc of
// 'radius') comes within 'clearance' of a surface of any height, up to 'limit'.
double FreeDistanceAhead(const Scene& scene, const Pose2& pose, double radius, double clearance,
                         double limit);

}  // namespace semchain::sim
