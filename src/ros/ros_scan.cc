#include "ros/ros_scan.h"

#include <charconv>
#include <cmath>

namespace semchain::ros1 {

double ShortestDouble(float value) {
  if (!std::isfinite(value)) return static_cast<double>(value);
  char text[32];
  const std::to_chars_result written = std::to_chars(text, text + sizeof(text), value);
  double result = static_cast<double>(value);
  std::from_chars(text, written.ptr, result);
  return result;
}

sensor_msgs::LaserScan ToLaserScanMsg(const carmen::Laser& laser, const std_msgs::Header& header) {
  const LaserScan& scan = laser.scan.scan;
  sensor_msgs::LaserScan msg;
  msg.header = header;
  const double last_beam =
      scan.ranges.empty() ? scan.angle_min : scan.BeamAngle(scan.ranges.size() - 1);
  msg.angle_min = static_cast<float>(scan.angle_min);
  msg.angle_max = static_cast<float>(last_beam);
  msg.angle_increment = static_cast<float>(scan.angle_increment);
  msg.time_increment = 0.0F;
  msg.scan_time = 0.0F;
  msg.range_min = 0.0F;
  msg.range_max = static_cast<float>(scan.max_range);
  msg.ranges.reserve(scan.ranges.size());
  for (const double range : scan.ranges) msg.ranges.push_back(static_cast<float>(range));
  if (laser.remissions.size() == scan.ranges.size()) {
    for (const double remission : laser.remissions) {
      msg.intensities.push_back(static_cast<float>(remission));
    }
  }
  return msg;
}

ImportedScan FromLaserScanMsg(const sensor_msgs::LaserScan& msg) {
  ImportedScan imported;
  LaserScan& scan = imported.scan;
  scan.angle_min = ShortestDouble(msg.angle_min);
  scan.angle_increment = ShortestDouble(msg.angle_increment);
  scan.max_range = ShortestDouble(msg.range_max);
  scan.ranges.reserve(msg.ranges.size());
  for (const float range : msg.ranges) {
    if (std::isfinite(range)) {
      scan.ranges.push_back(ShortestDouble(range));
    } else {
      scan.ranges.push_back(scan.max_range);
      ++imported.non_finite_ranges;
    }
  }
  if (msg.intensities.size() == msg.ranges.size()) {
    for (const float intensity : msg.intensities) {
      imported.intensities.push_back(std::isfinite(intensity) ? ShortestDouble(intensity) : 0.0);
    }
  }
  return imported;
}

}  // namespace semchain::ros1
