#include "ros/bag_time.h"

#include <cmath>
#include <limits>
#include <string>

#include "io/text_fields.h"

namespace semchain::ros1 {
namespace {

constexpr std::int64_t kNanosecondsPerSecond = 1'000'000'000;
// ros::Time's seconds are a uint32.
constexpr double kLatestRosSeconds = 4294967295.0;

std::int64_t RoundToNanoseconds(double seconds) {
  return std::llround(seconds * static_cast<double>(kNanosecondsPerSecond));
}

}  // namespace

std::int64_t ExportStampOffset(double earliest_seconds) {
  if (!std::isfinite(earliest_seconds) || RoundToNanoseconds(earliest_seconds) >= 1) return 0;
  return static_cast<std::int64_t>(std::ceil(1.0 - earliest_seconds));
}

Result<ros::Time> ToRosTime(double run_seconds, std::int64_t offset_seconds) {
  const double seconds = run_seconds + static_cast<double>(offset_seconds);
  if (!std::isfinite(run_seconds) || !(seconds > 0.0) || seconds > kLatestRosSeconds) {
    return Status::Error("stamp " + text::FormatDouble(run_seconds) + " s (+ " +
                         std::to_string(offset_seconds) +
                         " s) is not a ROS time (after 0, before 2^32 s)");
  }
  const std::int64_t nanoseconds =
      RoundToNanoseconds(run_seconds) + offset_seconds * kNanosecondsPerSecond;
  if (nanoseconds < 1)
    return Status::Error("stamp rounds to ROS time 0, which tf reads as 'latest'");
  ros::Time time;
  time.fromNSec(static_cast<std::uint64_t>(nanoseconds));
  return time;
}

double FromRosTime(const ros::Time& time, std::int64_t offset_seconds) {
  const std::int64_t nanoseconds = Nanoseconds(time) - offset_seconds * kNanosecondsPerSecond;
  return static_cast<double>(nanoseconds) / static_cast<double>(kNanosecondsPerSecond);
}

double FromRosSeconds(double ros_seconds, std::int64_t offset_seconds) {
  const std::int64_t nanoseconds =
      RoundToNanoseconds(ros_seconds) - offset_seconds * kNanosecondsPerSecond;
  return static_cast<double>(nanoseconds) / static_cast<double>(kNanosecondsPerSecond);
}

}  // namespace semchain::ros1
