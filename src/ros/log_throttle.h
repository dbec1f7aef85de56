#pragma once

#include <ros/console.h>

#include <mutex>
#include <optional>

// Throttled console messages timed on the wall clock. rosconsole's ROS_*_THROTTLE time the
// period on ros::Time, which under simulated time starts at the bag's first stamp and counts the
// last message as sent at 0: a bag starting at 1 s (as `semchain bag export` writes them) hides
// every throttled warning of its first seconds, the first included. Here the first message of a
// call site is always said, and the next ones at most once per period of wall time.
namespace semchain::ros1 {

class LogThrottle {
 public:
  explicit LogThrottle(double period_seconds) : period_seconds_(period_seconds) {}
  // Whether a message may be said now (and, if so, marks it said). Call sites are shared by the
  // node's threads.
  bool Due();

 private:
  const double period_seconds_;
  std::mutex mutex_;
  std::optional<double> last_said_;
};

}  // namespace semchain::ros1

#define SEMCHAIN_LOG_THROTTLE(log_macro, period, ...)                    \
  do {                                                                   \
    static ::semchain::ros1::LogThrottle semchain_log_throttle_(period); \
    if (semchain_log_throttle_.Due()) log_macro(__VA_ARGS__);            \
  } while (false)
#define SEMCHAIN_WARN_THROTTLE(period, ...) SEMCHAIN_LOG_THROTTLE(ROS_WARN, period, __VA_ARGS__)
#define SEMCHAIN_ERROR_THROTTLE(period, ...) SEMCHAIN_LOG_THROTTLE(ROS_ERROR, period, __VA_ARGS__)
