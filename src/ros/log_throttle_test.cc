#include "ros/log_throttle.h"

#include <gtest/gtest.h>

namespace semchain::ros1 {
namespace {

TEST(LogThrottleTest, TheFirstMessageIsSaidAtOnceThenOncePerPeriod) {
  // rosconsole's throttle, timed on a simulated clock that starts at 1 s, would say nothing here.
  LogThrottle hourly(3600.0);
  EXPECT_TRUE(hourly.Due());
  EXPECT_FALSE(hourly.Due());
  EXPECT_FALSE(hourly.Due());
}

TEST(LogThrottleTest, AZeroPeriodSaysEveryMessage) {
  LogThrottle always(0.0);
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(always.Due());
}

}  // namespace
}  // namespace semchain::ros1
