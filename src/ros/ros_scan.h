#pragma once

#include <sensor_msgs/LaserScan.h>

#include <cstddef>
#include <vector>

#include "io/carmen.h"
#include "sensors/laser_scan.h"

// Laser scans between CARMEN log records and sensor_msgs/LaserScan. A LaserScan holds float32
// ranges and angles, a log doubles: a range goes into the bag as the float nearest to it and
// comes back as the shortest decimal of that float ("2.8374", not 2.83739995956420898), so a
// scan that has been through a bag once goes through again unchanged, bit for bit.
namespace semchain::ros1 {

// The scan of 'laser' as a LaserScan with 'header'. angle_max is the last beam's angle;
// range_min is 0 (a log has no minimum); remissions of the same count become intensities.
sensor_msgs::LaserScan ToLaserScanMsg(const carmen::Laser& laser, const std_msgs::Header& header);

struct ImportedScan {
  LaserScan scan;                     // timestamp left 0: the caller knows the run's clock
  std::vector<double> intensities;    // empty when the message has none for every beam
  std::size_t non_finite_ranges = 0;  // NaN and ±inf readings, stored as max_range
};

// The scan of 'msg' for a log. A NaN or infinite reading (REP 117: invalid, too close, no
// return) becomes max_range, which is how a log says "no return".
ImportedScan FromLaserScanMsg(const sensor_msgs::LaserScan& msg);

// The double of the shortest decimal text that reads back as 'value' in float32.
double ShortestDouble(float value);

}  // namespace semchain::ros1
