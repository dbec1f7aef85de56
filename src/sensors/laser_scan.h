#pragma once

#include <cstddef>
#include <vector>

#include "core/pose2.h"

namespace semchain {

// One sweep of a planar range finder. Beam i points at angle_min + i * angle_increment in the
// laser frame; a reading >= max_range (or non-positive) means "no return".
struct LaserScan {
  double timestamp = 0.0;
  double angle_min = 0.0;        // radians
  double angle_increment = 0.0;  // radians
  double max_range = 0.0;        // metres
  std::vector<double> ranges;    // metres

  std::size_t size() const { return ranges.size(); }
  double BeamAngle(std::size_t i) const {
    return angle_min + static_cast<double>(i) * angle_increment;
  }
  bool IsReturn(std::size_t i) const { return ranges[i] > 0.0 && ranges[i] < max_range; }
};

// A laser scan with the poses a log gives with it: the laser's pose and the robot's odometry
// pose at the scan's time, both in the odometry frame. 'laser_offset' = odom⁻¹ ⊕ laser.
struct StampedScan {
  LaserScan scan;
  Pose2 odometry;    // robot pose from odometry
  Pose2 laser_pose;  // laser pose from odometry
  Pose2 LaserOffset() const { return odometry.Between(laser_pose); }
};

}  // namespace semchain
