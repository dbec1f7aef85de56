#include "ros/scan_import.h"

#include <nav_msgs/Odometry.h>
#include <sensor_msgs/LaserScan.h>

#include <cstdio>
#include <optional>
#include <string>
#include <utility>

#include "core/angles.h"
#include "ros/bag_time.h"
#include "ros/ros_geometry.h"
#include "ros/ros_scan.h"

namespace semchain::ros1 {
namespace {

// A laser leaning further than this out of the floor plane does not measure a 2D scan.
constexpr double kMaxLaserTiltRadians = DegToRad(5.0);

struct Velocity {
  double linear = 0.0;
  double angular = 0.0;
};

// The odometry topic's velocities by stamp, for the tv and rv fields of the log.
Result<std::map<std::int64_t, Velocity>> OdometryVelocities(BagReader& reader,
                                                            const std::string& topic) {
  std::map<std::int64_t, Velocity> velocities;
  const Status status = reader.ForEach<nav_msgs::Odometry>(
      {topic}, [&velocities](const nav_msgs::Odometry& msg, const BagMessage&) {
        velocities[Nanoseconds(msg.header.stamp)] = {msg.twist.twist.linear.x,
                                                     msg.twist.twist.angular.z};
        return Status::Ok();
      });
  if (!status.ok()) return status;
  return velocities;
}

std::string Number(double value) {
  char text[40];
  std::snprintf(text, sizeof(text), "%.9g", value);
  return text;
}

void AddHeader(const carmen::Laser& first, const ImportContext& context, carmen::Log* log) {
  const BagImportOptions& options = context.options;
  const auto comment = [log](const std::string& text) {
    log->records.push_back(carmen::Other{"# " + text});
  };
  comment("CARMEN Logfile written by semchain bag import");
  comment("scans from " + options.topics.scan + ", odometry " + options.frames.odom + " -> " +
          options.frames.base + " from tf at each scan");
  comment("per scan: ODOM (odometry), TRUEPOS (truth, when the bag has it), ROBOTLASER1 (scan)");
  const LaserScan& scan = first.scan.scan;
  const auto param = [log](const std::string& name, const std::string& value) {
    log->records.push_back(carmen::Param{name, value, ""});
  };
  param("robot_frontlaser_offset", Number(first.scan.LaserOffset().x));
  param("laser_front_laser_fov",
        Number(RadToDeg(scan.angle_increment * static_cast<double>(scan.size() - 1))));
  param("laser_front_laser_resolution", Number(RadToDeg(scan.angle_increment)));
  param("robot_front_laser_max", Number(scan.max_range));
}

// Turns scan messages into log records; one instance per import.
class ScanConverter {
 public:
  ScanConverter(const BagTransforms& transforms, const TruthByStamp& truth,
                const std::map<std::int64_t, Velocity>& velocities, ImportContext& context)
      : transforms_(transforms), truth_(truth), velocities_(velocities), context_(context) {}

  Status Add(const sensor_msgs::LaserScan& msg, const std::string& where);
  // The log: the header made from the first scan, then every scan's records.
  ImportedLog Finish();
  std::size_t scans() const { return result_.scans; }
  std::size_t skipped() const { return result_.skipped_scans; }
  const std::string& first_skip_reason() const { return first_skip_reason_; }

 private:
  Result<Pose2> LaserOffset(const std::string& laser_frame, const ros::Time& stamp,
                            const std::string& where) const;

  const BagTransforms& transforms_;
  const TruthByStamp& truth_;
  const std::map<std::int64_t, Velocity>& velocities_;
  ImportContext& context_;
  ImportedLog result_;
  std::vector<carmen::Record> records_;
  std::optional<carmen::Laser> first_;
  std::string first_skip_reason_;
};

Result<Pose2> ScanConverter::LaserOffset(const std::string& laser_frame, const ros::Time& stamp,
                                         const std::string& where) const {
  const std::string& base = context_.options.frames.base;
  Result<Eigen::Isometry3d> laser = transforms_.Lookup(base, laser_frame, stamp);
  if (!laser.ok()) {
    return Status::Error(where + ": no pose of the laser: " + laser.status().message() +
                         " (tf frames: " + transforms_.Frames() + ")");
  }
  if (TiltRadians(*laser) > kMaxLaserTiltRadians) {
    return Status::Error(where + ": laser frame " + laser_frame + " leans " +
                         Number(RadToDeg(TiltRadians(*laser))) + " deg out of the plane of " +
                         base + "; a 2D log needs a level laser");
  }
  return PlanarPose(*laser);
}

Status ScanConverter::Add(const sensor_msgs::LaserScan& msg, const std::string& where) {
  const BagFrames& frames = context_.options.frames;
  if (msg.header.stamp.isZero()) return Status::Error(where + ": stamp 0");
  Result<Eigen::Isometry3d> odometry =
      transforms_.Lookup(frames.odom, frames.base, msg.header.stamp);
  if (!odometry.ok()) {
    if (first_skip_reason_.empty()) first_skip_reason_ = odometry.status().message();
    ++result_.skipped_scans;
    return Status::Ok();
  }
  Result<Pose2> offset =
      LaserOffset(TfFrameId(msg.header.frame_id, frames.laser), msg.header.stamp, where);
  if (!offset.ok()) return offset.status();
  ImportedScan imported = FromLaserScanMsg(msg);
  if (!(imported.scan.max_range > 0.0) || imported.scan.ranges.size() < 2) {
    return Status::Error(where + ": range_max " + Number(imported.scan.max_range) + " and " +
                         std::to_string(imported.scan.ranges.size()) + " beams: not a scan");
  }
  const std::int64_t stamp_ns = Nanoseconds(msg.header.stamp);
  const double stamp = FromRosTime(msg.header.stamp, context_.stamp_offset_seconds);
  const carmen::Stamp log_stamp{stamp, "semchain", stamp};
  const Pose2 robot = PlanarPose(*odometry);
  const auto velocity = velocities_.find(stamp_ns);
  const Velocity v = velocity == velocities_.end() ? Velocity{} : velocity->second;
  records_.push_back(carmen::Odometry{robot, v.linear, v.angular, 0.0, log_stamp});
  const auto truth = truth_.find(stamp_ns);
  if (truth != truth_.end()) records_.push_back(carmen::TruePose{truth->second, robot, log_stamp});
  carmen::Laser laser;
  laser.kind = carmen::Laser::Kind::kRobotLaser1;
  laser.scan.scan = std::move(imported.scan);
  laser.scan.scan.timestamp = stamp;
  laser.scan.odometry = robot;
  laser.scan.laser_pose = robot * *offset;
  laser.remission_mode = imported.intensities.empty() ? 0 : 1;
  laser.remissions = std::move(imported.intensities);
  laser.tv = v.linear;
  laser.rv = v.angular;
  laser.stamp = log_stamp;
  if (!first_) {
    first_ = laser;
    result_.first_stamp = stamp;
  }
  records_.push_back(std::move(laser));
  result_.last_stamp = stamp;
  ++result_.scans;
  result_.non_finite_ranges += imported.non_finite_ranges;
  return Status::Ok();
}

ImportedLog ScanConverter::Finish() {
  ImportedLog result = std::move(result_);
  AddHeader(*first_, context_, &result.log);
  for (carmen::Record& record : records_) result.log.records.push_back(std::move(record));
  records_.clear();
  return result;
}

Status CheckConnected(const BagTransforms& transforms, const std::string& target,
                      const std::string& source, const std::string& what) {
  if (transforms.Connects(target, source)) return Status::Ok();
  return Status::Error("no " + what + ": tf has no transform " + target + " -> " + source +
                       " (tf frames: " + transforms.Frames() + ")");
}

}  // namespace

Result<ImportedLog> ImportScans(BagReader& reader, const BagTransforms& transforms,
                                const TruthByStamp& truth, ImportContext& context) {
  const BagImportOptions& options = context.options;
  SEMCHAIN_RETURN_IF_ERROR(reader.Require<sensor_msgs::LaserScan>(options.topics.scan));
  SEMCHAIN_RETURN_IF_ERROR(
      CheckConnected(transforms, options.frames.odom, options.frames.base, "odometry")
          .WithContext(reader.path().string()));
  Result<std::map<std::int64_t, Velocity>> velocities =
      OdometryVelocities(reader, options.topics.odom);
  if (!velocities.ok()) return velocities.status();
  ScanConverter converter(transforms, truth, *velocities, context);
  SEMCHAIN_RETURN_IF_ERROR(reader.ForEach<sensor_msgs::LaserScan>(
      {options.topics.scan},
      [&converter](const sensor_msgs::LaserScan& msg, const BagMessage& message) {
        return converter.Add(msg, message.where);
      }));
  if (converter.scans() == 0 && converter.skipped() == 0) {
    return Status::Error(reader.path().string() + ": no scans on " + options.topics.scan);
  }
  if (converter.scans() == 0) {
    return Status::Error(reader.path().string() + ": none of the " +
                         std::to_string(converter.skipped()) + " scans on " + options.topics.scan +
                         " has odometry: " + converter.first_skip_reason());
  }
  if (converter.skipped() > 0) {
    context.warnings.push_back(std::to_string(converter.skipped()) + " scans on " +
                               options.topics.scan + " left out: no odometry at their stamps (" +
                               converter.first_skip_reason() + ")");
  }
  return converter.Finish();
}

}  // namespace semchain::ros1
