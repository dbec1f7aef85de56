// Parsing of single CARMEN log lines (DESIGN.md §5.1). Field layouts follow CARMEN's
// logger (readlog.c / writelog.c); every malformed line is one error naming file, line and
// record type.
#include <cmath>
#include <string_view>
#include <utility>

#include "core/angles.h"
#include "io/carmen.h"
#include "io/text_fields.h"

namespace semchain::carmen {
namespace {

using text::FieldReader;

constexpr std::size_t kStampFields = 3;  // ts host logger_ts

// Reads three numbers into 'pose'. The fields are assigned, not passed through Pose2's
// constructor, so that a log's angles come back exactly as written.
Status ReadPose(FieldReader& fields, std::string_view name, Pose2* pose) {
  const std::string prefix(name);
  SEMCHAIN_RETURN_IF_ERROR(fields.Double(prefix + " x", &pose->x));
  SEMCHAIN_RETURN_IF_ERROR(fields.Double(prefix + " y", &pose->y));
  return fields.Double(prefix + " theta", &pose->theta);
}

Status ReadStamp(FieldReader& fields, Stamp* stamp) {
  SEMCHAIN_RETURN_IF_ERROR(fields.Double("timestamp", &stamp->timestamp));
  SEMCHAIN_RETURN_IF_ERROR(fields.Word("host", &stamp->host));
  SEMCHAIN_RETURN_IF_ERROR(fields.Double("logger timestamp", &stamp->logger_timestamp));
  return fields.End();
}

// Checks that exactly 'count' items and then 'tail' more fields are left.
Status CheckCount(const FieldReader& fields, int count, std::size_t tail, const char* items) {
  const std::size_t left = fields.remaining();
  const std::size_t expected = static_cast<std::size_t>(count) + tail;
  if (left == expected) return Status::Ok();
  if (left < tail) {
    return fields.Error("truncated line: expected " + std::to_string(expected) +
                        " fields after the number of " + items + ", got " + std::to_string(left));
  }
  return fields.Error("expected " + std::to_string(count) + " " + items + ", got " +
                      std::to_string(left - tail));
}

Status ReadValues(FieldReader& fields, const char* name, int count, std::vector<double>* values) {
  values->resize(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    SEMCHAIN_RETURN_IF_ERROR(fields.Double(name, &(*values)[static_cast<std::size_t>(i)], i));
  }
  return Status::Ok();
}

// Beam geometry of a FLASER scan, see ReadOptions.
void SetFlaserGeometry(const ReadOptions& options, LaserScan* scan) {
  const std::size_t n = scan->ranges.size();
  double increment = options.flaser_resolution_radians;
  if (increment <= 0.0 && n >= 2) {
    increment = options.flaser_fov_radians / static_cast<double>(n % 2 == 1 ? n - 1 : n);
  }
  scan->angle_min = -0.5 * options.flaser_fov_radians;
  scan->angle_increment = increment;
  scan->max_range = options.flaser_max_range;
}

// FLASER n r1..rn x y theta odom_x odom_y odom_theta ts host logger_ts
Status ParseFlaser(FieldReader& fields, const ReadOptions& options, Laser* laser) {
  laser->kind = Laser::Kind::kFlaser;
  int count = 0;
  SEMCHAIN_RETURN_IF_ERROR(fields.Count("number of ranges", &count));
  SEMCHAIN_RETURN_IF_ERROR(CheckCount(fields, count, 6 + kStampFields, "ranges"));
  SEMCHAIN_RETURN_IF_ERROR(ReadValues(fields, "range", count, &laser->scan.scan.ranges));
  SEMCHAIN_RETURN_IF_ERROR(ReadPose(fields, "laser", &laser->scan.laser_pose));
  SEMCHAIN_RETURN_IF_ERROR(ReadPose(fields, "odometry", &laser->scan.odometry));
  SEMCHAIN_RETURN_IF_ERROR(ReadStamp(fields, &laser->stamp));
  SetFlaserGeometry(options, &laser->scan.scan);
  laser->scan.scan.timestamp = laser->stamp.timestamp;
  return Status::Ok();
}

// ROBOTLASER1 laser_type start_angle fov resolution max_range accuracy remission_mode
//   n r1..rn m rem1..remm laser_x laser_y laser_theta robot_x robot_y robot_theta
//   tv rv forward_safety side_safety turn_axis ts host logger_ts
Status ParseRobotLaser1(FieldReader& fields, Laser* laser) {
  constexpr std::size_t kTail = 6 + 5 + kStampFields;
  laser->kind = Laser::Kind::kRobotLaser1;
  LaserScan& scan = laser->scan.scan;
  SEMCHAIN_RETURN_IF_ERROR(fields.Int("laser type", &laser->laser_type));
  SEMCHAIN_RETURN_IF_ERROR(fields.Double("start angle", &scan.angle_min));
  SEMCHAIN_RETURN_IF_ERROR(fields.Double("fov", &laser->fov));
  SEMCHAIN_RETURN_IF_ERROR(fields.Double("resolution", &scan.angle_increment));
  SEMCHAIN_RETURN_IF_ERROR(fields.Double("max range", &scan.max_range));
  SEMCHAIN_RETURN_IF_ERROR(fields.Double("accuracy", &laser->accuracy));
  SEMCHAIN_RETURN_IF_ERROR(fields.Int("remission mode", &laser->remission_mode));
  int count = 0;
  SEMCHAIN_RETURN_IF_ERROR(fields.Count("number of ranges", &count));
  if (fields.remaining() < static_cast<std::size_t>(count) + 1 + kTail) {
    return CheckCount(fields, count, 1 + kTail, "ranges");
  }
  SEMCHAIN_RETURN_IF_ERROR(ReadValues(fields, "range", count, &scan.ranges));
  SEMCHAIN_RETURN_IF_ERROR(fields.Count("number of remissions", &count));
  SEMCHAIN_RETURN_IF_ERROR(CheckCount(fields, count, kTail, "remissions"));
  SEMCHAIN_RETURN_IF_ERROR(ReadValues(fields, "remission", count, &laser->remissions));
  SEMCHAIN_RETURN_IF_ERROR(ReadPose(fields, "laser", &laser->scan.laser_pose));
  SEMCHAIN_RETURN_IF_ERROR(ReadPose(fields, "robot", &laser->scan.odometry));
  SEMCHAIN_RETURN_IF_ERROR(fields.Double("tv", &laser->tv));
  SEMCHAIN_RETURN_IF_ERROR(fields.Double("rv", &laser->rv));
  SEMCHAIN_RETURN_IF_ERROR(fields.Double("forward safety", &laser->forward_safety));
  SEMCHAIN_RETURN_IF_ERROR(fields.Double("side safety", &laser->side_safety));
  SEMCHAIN_RETURN_IF_ERROR(fields.Double("turn axis", &laser->turn_axis));
  SEMCHAIN_RETURN_IF_ERROR(ReadStamp(fields, &laser->stamp));
  scan.timestamp = laser->stamp.timestamp;
  return Status::Ok();
}

// ODOM x y theta tv rv accel ts host logger_ts
Status ParseOdometry(FieldReader& fields, Odometry* odometry) {
  SEMCHAIN_RETURN_IF_ERROR(ReadPose(fields, "odometry", &odometry->pose));
  SEMCHAIN_RETURN_IF_ERROR(fields.Double("tv", &odometry->tv));
  SEMCHAIN_RETURN_IF_ERROR(fields.Double("rv", &odometry->rv));
  SEMCHAIN_RETURN_IF_ERROR(fields.Double("accel", &odometry->accel));
  return ReadStamp(fields, &odometry->stamp);
}

// TRUEPOS true_x true_y true_theta odom_x odom_y odom_theta ts host logger_ts
Status ParseTruePose(FieldReader& fields, TruePose* true_pose) {
  SEMCHAIN_RETURN_IF_ERROR(ReadPose(fields, "true", &true_pose->truth));
  SEMCHAIN_RETURN_IF_ERROR(ReadPose(fields, "odometry", &true_pose->odometry));
  return ReadStamp(fields, &true_pose->stamp);
}

// PARAM name value [rest]
Status ParseParam(FieldReader& fields, Param* param) {
  SEMCHAIN_RETURN_IF_ERROR(fields.Word("name", &param->name));
  SEMCHAIN_RETURN_IF_ERROR(fields.Word("value", &param->value));
  param->rest = fields.Rest();
  return Status::Ok();
}

// Parses the fields after the type word into a default-constructed 'T' with 'parse'.
template <typename T, typename Parse>
Result<Record> ParseAs(FieldReader& fields, Parse parse) {
  T record;
  SEMCHAIN_RETURN_IF_ERROR(parse(fields, &record));
  return Record(std::move(record));
}

}  // namespace

Result<Record> ParseLine(const std::string& line, const std::string& where,
                         const ReadOptions& options) {
  const std::size_t begin = line.find_first_not_of(" \t");
  const std::size_t end = line.find_first_of(" \t\r", begin);
  const std::string_view type = begin == std::string::npos
                                    ? std::string_view()
                                    : std::string_view(line).substr(begin, end - begin);
  const std::string_view rest = end == std::string::npos ? "" : std::string_view(line).substr(end);
  FieldReader fields(rest, where + ": " + std::string(type));
  if (type == "FLASER") {
    return ParseAs<Laser>(fields, [&options](FieldReader& f, Laser* laser) {
      return ParseFlaser(f, options, laser);
    });
  }
  if (type == "ROBOTLASER1") return ParseAs<Laser>(fields, ParseRobotLaser1);
  if (type == "ODOM") return ParseAs<Odometry>(fields, ParseOdometry);
  if (type == "TRUEPOS") return ParseAs<TruePose>(fields, ParseTruePose);
  if (type == "PARAM") return ParseAs<Param>(fields, ParseParam);
  return Record(Other{line});
}

Status ApplyParam(const Param& param, const std::string& where, ReadOptions* options) {
  double* target = nullptr;
  double scale = 1.0;
  if (param.name == "laser_front_laser_fov") {
    target = &options->flaser_fov_radians;
    scale = DegToRad(1.0);
  } else if (param.name == "laser_front_laser_resolution") {
    target = &options->flaser_resolution_radians;
    scale = DegToRad(1.0);
  } else if (param.name == "robot_front_laser_max") {
    target = &options->flaser_max_range;
  } else {
    return Status::Ok();
  }
  double value = 0.0;
  if (!text::ParseDouble(param.value, &value) || !std::isfinite(value) || value <= 0.0) {
    return Status::Error(where + ": PARAM " + param.name + ": '" + param.value +
                         "' is not a positive number");
  }
  *target = value * scale;
  return Status::Ok();
}

}  // namespace semchain::carmen
