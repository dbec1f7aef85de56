#pragma once

#include <vector>

#include "io/carmen.h"
#include "sensors/laser_scan.h"

// Wheel odometry that ignores the direction of travel. The base of the Freiburg 079 log
// integrated the speed's magnitude: while the robot backs up, its ODOM records report a negative
// translational velocity but a pose that moves forward (126 of the log's 4934 scan steps, up to
// 1.5 m in one step of the filter). No scan matcher absorbs that, and the RBPF fed it diverged
// (0.90 m relation error). The odometry's own velocity tells the direction, so the step is
// reversed where the two contradict each other.
namespace semchain::mapping {

struct ReversedOdometryRepair {
  int steps = 0;        // scan-to-scan odometry steps whose translation was reversed
  double meters = 0.0;  // their total length
};

// For each pair of consecutive scans whose odometry moved forward (in the first scan's frame)
// while the ODOM record nearest to the middle of the interval has a translational velocity below
// −'min_speed', reverses that step's translation and re-chains the odometry and laser poses of
// every later scan. Without ODOM records nothing changes.
ReversedOdometryRepair RepairReversedOdometry(const std::vector<const carmen::Odometry*>& records,
                                              std::vector<StampedScan>* scans,
                                              double min_speed = 0.01);

}  // namespace semchain::mapping
