#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/pose2.h"
#include "core/status.h"
#include "sensors/laser_scan.h"

// CARMEN logs (DESIGN.md §5.1): ODOM, FLASER, ROBOTLASER1, TRUEPOS and PARAM lines, plain or
// gzip-compressed. Other line types (NEFF, SYNC, RLASER, RAWLASER…) and '#' comment lines are
// kept as raw text (Other) so that a read-write round trip keeps them; blank lines are dropped.
// Poses and angles are kept exactly as written (not re-wrapped into (-pi, pi]).
namespace semchain::carmen {

// Fields every timed message carries at its end: "ts host logger_ts".
struct Stamp {
  double timestamp = 0.0;
  std::string host = "semchain";
  double logger_timestamp = 0.0;
};

// ODOM x y theta tv rv accel ts host logger_ts
struct Odometry {
  Pose2 pose;
  double tv = 0.0;
  double rv = 0.0;
  double accel = 0.0;
  Stamp stamp;
};

// FLASER n r1..rn x y theta odom_x odom_y odom_theta ts host logger_ts
// ROBOTLASER1 laser_type start_angle fov resolution max_range accuracy remission_mode
//   n r1..rn m rem1..remm laser_x laser_y laser_theta robot_x robot_y robot_theta
//   tv rv forward_safety side_safety turn_axis ts host logger_ts
struct Laser {
  enum class Kind { kFlaser, kRobotLaser1 };
  Kind kind = Kind::kFlaser;
  StampedScan scan;  // scan.scan.timestamp == stamp.timestamp
  // ROBOTLASER1 only: the fields kept for a faithful round trip. 'fov' 0 is written as
  // (n - 1) * angle_increment, CARMEN's relation between the three.
  int laser_type = 0;
  double fov = 0.0;
  double accuracy = 0.0;
  int remission_mode = 0;
  std::vector<double> remissions;
  double tv = 0.0, rv = 0.0, forward_safety = 0.0, side_safety = 0.0, turn_axis = 0.0;
  Stamp stamp;
};

// TRUEPOS true_x true_y true_theta odom_x odom_y odom_theta ts host logger_ts
struct TruePose {
  Pose2 truth;
  Pose2 odometry;
  Stamp stamp;
};

// PARAM name value [rest]: 'rest' is what follows the value in the log (usually
// "ts host logger_ts", in older logs "host ts"), kept verbatim.
struct Param {
  std::string name;
  std::string value;
  std::string rest;
};

// A line of a type this reader does not interpret, kept verbatim.
struct Other {
  std::string line;
};

using Record = std::variant<Odometry, Laser, TruePose, Param, Other>;

struct Log {
  std::vector<Record> records;  // in file order

  std::vector<const Laser*> Lasers() const;
  std::vector<const Odometry*> Odometries() const;
  std::vector<const TruePose*> TruePoses() const;
};

// How FLASER beam angles are laid out. FLASER lines carry only the ranges; like CARMEN's own
// reader (readlog.c, carmen_laser_guess_fov / carmen_laser_guess_angle_increment) we take a
// SICK LMS looking ahead: beam i is at -fov/2 + i * increment, where a scan of an odd number n
// of beams spans the fov exactly (increment = fov / (n - 1): 181 beams at 1°, 361 at 0.5°) and
// an even n is such a scan with its last beam dropped (increment = fov / n: 180 beams at 1°,
// 360 at 0.5°, ending half a degree or a degree short of +fov/2). ReadLog() lets a log's PARAM
// lines laser_front_laser_fov and laser_front_laser_resolution (degrees) and
// robot_front_laser_max (metres) override these for the lines that follow them.
struct ReadOptions {
  double flaser_fov_radians = 3.14159265358979323846;  // FLASER beams span this, centred ahead
  double flaser_resolution_radians = 0.0;              // angle between beams; 0 = derived as above
  // Readings >= this are "no return" (LaserScan::max_range). 80 m is CARMEN's FLASER default;
  // the SICK LMS values above it in the public logs (81.83, 81.91) are error codes.
  double flaser_max_range = 80.0;
};

// Applies a PARAM line that describes the front laser (see ReadOptions) to 'options'; other
// parameters are ignored. 'where' prefixes errors ("file:line").
Status ApplyParam(const Param& param, const std::string& where, ReadOptions* options);

// Reads a CARMEN log; a path ending in ".gz" is decompressed. A malformed line is an error
// naming the file and line number ("log.clf:12: FLASER: expected 361 ranges, got 200");
// NaN or infinite values are errors.
Result<Log> ReadLog(const std::filesystem::path& path, const ReadOptions& options = {});

// ReadLog on the text of a log; 'source' names it in errors.
Result<Log> ParseLog(std::string_view text, const std::string& source,
                     const ReadOptions& options = {});

// Parses one log line (without newline); 'where' prefixes errors ("file:line").
Result<Record> ParseLine(const std::string& line, const std::string& where,
                         const ReadOptions& options = {});

// Formats one record as a log line (without newline), with enough digits to round-trip.
std::string FormatRecord(const Record& record);

// Writes a log atomically; a path ending in ".gz" is compressed.
Status WriteLog(const std::filesystem::path& path, const Log& log);

}  // namespace semchain::carmen
