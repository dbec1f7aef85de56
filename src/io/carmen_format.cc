// Formatting of CARMEN log lines: the layouts carmen_parse.cc reads, with every number in its
// shortest round-trip form so that a write-read cycle returns exactly the same values.
#include <string>
#include <type_traits>

#include "io/carmen.h"
#include "io/text_fields.h"

namespace semchain::carmen {
namespace {

void Append(double value, std::string* out) {
  out->push_back(' ');
  text::AppendDouble(value, out);
}

void Append(int value, std::string* out) { *out += ' ' + std::to_string(value); }

void Append(const Pose2& pose, std::string* out) {
  Append(pose.x, out);
  Append(pose.y, out);
  Append(pose.theta, out);
}

void Append(const std::vector<double>& values, std::string* out) {
  Append(static_cast<int>(values.size()), out);
  for (const double value : values) Append(value, out);
}

// A host name is one field; an empty one would shift every field after it.
void Append(const Stamp& stamp, std::string* out) {
  Append(stamp.timestamp, out);
  *out += ' ' + (stamp.host.empty() ? std::string("nohost") : stamp.host);
  Append(stamp.logger_timestamp, out);
}

std::string FormatLaser(const Laser& laser) {
  const LaserScan& scan = laser.scan.scan;
  std::string line;
  line.reserve(32 + 8 * scan.ranges.size());
  if (laser.kind == Laser::Kind::kFlaser) {
    line = "FLASER";
    Append(scan.ranges, &line);
    Append(laser.scan.laser_pose, &line);
    Append(laser.scan.odometry, &line);
    Append(laser.stamp, &line);
    return line;
  }
  const double fov = laser.fov != 0.0 || scan.ranges.empty()
                         ? laser.fov
                         : static_cast<double>(scan.ranges.size() - 1) * scan.angle_increment;
  line = "ROBOTLASER1";
  Append(laser.laser_type, &line);
  for (const double value :
       {scan.angle_min, fov, scan.angle_increment, scan.max_range, laser.accuracy}) {
    Append(value, &line);
  }
  Append(laser.remission_mode, &line);
  Append(scan.ranges, &line);
  Append(laser.remissions, &line);
  Append(laser.scan.laser_pose, &line);
  Append(laser.scan.odometry, &line);
  for (const double value :
       {laser.tv, laser.rv, laser.forward_safety, laser.side_safety, laser.turn_axis}) {
    Append(value, &line);
  }
  Append(laser.stamp, &line);
  return line;
}

std::string FormatOdometry(const Odometry& odometry) {
  std::string line = "ODOM";
  Append(odometry.pose, &line);
  Append(odometry.tv, &line);
  Append(odometry.rv, &line);
  Append(odometry.accel, &line);
  Append(odometry.stamp, &line);
  return line;
}

std::string FormatTruePose(const TruePose& true_pose) {
  std::string line = "TRUEPOS";
  Append(true_pose.truth, &line);
  Append(true_pose.odometry, &line);
  Append(true_pose.stamp, &line);
  return line;
}

std::string FormatParam(const Param& param) {
  std::string line = "PARAM " + param.name + " " + param.value;
  if (!param.rest.empty()) line += " " + param.rest;
  return line;
}

}  // namespace

std::string FormatRecord(const Record& record) {
  return std::visit(
      [](const auto& r) -> std::string {
        using T = std::decay_t<decltype(r)>;
        if constexpr (std::is_same_v<T, Laser>) {
          return FormatLaser(r);
        } else if constexpr (std::is_same_v<T, Odometry>) {
          return FormatOdometry(r);
        } else if constexpr (std::is_same_v<T, TruePose>) {
          return FormatTruePose(r);
        } else if constexpr (std::is_same_v<T, Param>) {
          return FormatParam(r);
        } else {
          static_assert(std::is_same_v<T, Other>);
          return r.line;
        }
      },
      record);
}

}  // namespace semchain::carmen
