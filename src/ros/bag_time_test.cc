#include "ros/bag_time.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace semchain::ros1 {
namespace {

TEST(BagTimeTest, ShiftsOnlyRunsThatStartAtOrBeforeZero) {
  EXPECT_EQ(ExportStampOffset(0.0), 1);
  EXPECT_EQ(ExportStampOffset(1e-10), 1);  // rounds to ROS time 0
  EXPECT_EQ(ExportStampOffset(-0.5), 2);
  EXPECT_EQ(ExportStampOffset(0.1), 0);
  EXPECT_EQ(ExportStampOffset(1134864643.12418), 0);  // a robot's clock
}

TEST(BagTimeTest, RoundTripsToTheNanosecond) {
  // Stamps summed in steps of 0.1 s, as the simulator makes them.
  double t = 0.0;
  for (int i = 0; i < 1000; ++i, t += 0.1) {
    const Result<ros::Time> time = ToRosTime(t, 1);
    ASSERT_TRUE(time.ok());
    EXPECT_NEAR(FromRosTime(*time, 1), t, 1e-9);
    EXPECT_EQ(FromRosTime(*time, 1), FromRosSeconds(FromRosTime(*time, 0), 1));
  }
  const Result<ros::Time> time = ToRosTime(0.30000000000000004, 1);
  ASSERT_TRUE(time.ok());
  EXPECT_EQ(Nanoseconds(*time), 1'300'000'000);
  EXPECT_EQ(FromRosTime(*time, 1), 0.3);  // the decimal, not 0.30000000000000004
  const Result<ros::Time> robot = ToRosTime(1134864643.12418, 0);
  ASSERT_TRUE(robot.ok());
  EXPECT_NEAR(FromRosTime(*robot, 0), 1134864643.12418, 1e-6);
}

TEST(BagTimeTest, RefusesWhatIsNoRosTime) {
  EXPECT_FALSE(ToRosTime(0.0, 0).ok());  // tf reads 0 as "latest"
  EXPECT_FALSE(ToRosTime(-1.0, 0).ok());
  EXPECT_FALSE(ToRosTime(std::numeric_limits<double>::quiet_NaN(), 1).ok());
  EXPECT_FALSE(ToRosTime(5e9, 0).ok());
  EXPECT_TRUE(ToRosTime(0.0, 1).ok());
}

}  // namespace
}  // namespace semchain::ros1
