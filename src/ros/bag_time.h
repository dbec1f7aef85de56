#pragma once

#include <ros/time.h>

#include <cstdint>

#include "core/status.h"

// Run time (seconds as a double, what logs and detections.jsonl hold) and ROS time (whole
// nanoseconds, never 0: tf reads time 0 as "the latest"). A run's stamps go into a bag as they
// are when the earliest is positive; the simulator's start at 0, so then a whole number of
// seconds is added to every stamp (ExportStampOffset: the earliest lands in [1 s, 2 s)). The
// offset travels in the bag's run info and `bag import` subtracts it, so a run comes back with
// its own stamps, to the nanosecond.
namespace semchain::ros1 {

// The whole seconds `bag export` adds to stamps whose earliest is 'earliest_seconds': 0 when
// that is at least 1 ns, else the seconds that move it to between 1 and 2 s.
std::int64_t ExportStampOffset(double earliest_seconds);

// 'run_seconds' + 'offset_seconds' rounded to the nanosecond; an error when that is not a valid
// ROS time (not finite, not after 0, or past 2^32 s).
Result<ros::Time> ToRosTime(double run_seconds, std::int64_t offset_seconds);

// The run time of 'time': its nanoseconds less the offset, in seconds (the double nearest the
// decimal number of nanoseconds, so 1.3 s comes back as 1.3, not 1.3000000000000000444).
double FromRosTime(const ros::Time& time, std::int64_t offset_seconds);

// The same for a stamp given in ROS seconds (a detections.jsonl record on the bag's clock).
double FromRosSeconds(double ros_seconds, std::int64_t offset_seconds);

// Whole nanoseconds of a ROS time, for exact comparisons of stamps.
inline std::int64_t Nanoseconds(const ros::Time& time) {
  return static_cast<std::int64_t>(time.toNSec());
}

}  // namespace semchain::ros1
