#pragma once

#include "core/pose2.h"
#include "core/rng.h"
#include "sensors/laser_scan.h"
#include "sim/scene.h"
#include "sim/world.h"

// The simulated 2D lidar (DESIGN.md §3.1): a planar scan at the lidar's mounting height, so
// that a solid lower than the scan plane is invisible to it (seed 004, obstacle B).
namespace semchain::sim {

// The lidar's pose on the robot: 'forward_offset' ahead of the robot centre, looking ahead.
Pose2 RobotFromLidar(const LidarSpec& spec);

// The empty scan of 'spec' (angles and max range set, no ranges). Beams are centred on the
// heading: a scan narrower than 360° spans it end to end (increment = fov / (beams - 1), like a
// SICK LMS); a full circle has 'beams' equal sectors starting behind the robot (angle_min = -π,
// increment = 2π / beams), so that no direction is measured twice.
LaserScan MakeEmptyScan(const LidarSpec& spec);

// One scan by the lidar of 'spec' on a robot at 'robot_pose' (world frame) in 'scene': each
// beam's range is the nearest surface whose vertical extent contains the scan plane, plus
// Gaussian noise of std 'spec.noise_std' drawn from 'rng'; a beam with no surface within
// max_range, or whose noisy range reaches it, reads exactly max_range ("no return").
LaserScan SimulateScan(const Scene& scene, const LidarSpec& spec, const Pose2& robot_pose,
                       double timestamp, Rng& rng);

}  // namespace semchain::sim
