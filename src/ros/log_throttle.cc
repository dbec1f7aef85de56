#include "ros/log_throttle.h"

#include <ros/time.h>

namespace semchain::ros1 {

bool LogThrottle::Due() {
  const double now = ::ros::WallTime::now().toSec();
  const std::lock_guard<std::mutex> lock(mutex_);
  if (last_said_ && now - *last_said_ < period_seconds_) return false;
  last_said_ = now;
  return true;
}

}  // namespace semchain::ros1
