#include "ros/ros_scan.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace semchain::ros1 {
namespace {

TEST(RosScanTest, ShortestDoubleReadsBackAsTheSameFloat) {
  EXPECT_EQ(ShortestDouble(2.8374f), 2.8374);
  EXPECT_EQ(ShortestDouble(12.0f), 12.0);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> range(0.0, 80.0);
  for (int i = 0; i < 100000; ++i) {
    const float value = static_cast<float>(range(rng));
    const double shortest = ShortestDouble(value);
    ASSERT_EQ(static_cast<float>(shortest), value) << shortest;
    ASSERT_EQ(ShortestDouble(static_cast<float>(shortest)), shortest);
  }
}

TEST(RosScanTest, ALogScanGoesOutAsFloatsAndComesBack) {
  carmen::Laser laser;
  LaserScan& scan = laser.scan.scan;
  scan.angle_min = -3.14159265358979;
  scan.angle_increment = 2.0 * 3.14159265358979 / 360.0;
  scan.max_range = 12.0;
  for (int i = 0; i < 360; ++i) scan.ranges.push_back(0.5 + 0.0123456789 * i);
  scan.ranges[7] = 12.0;  // no return
  std_msgs::Header header;
  header.frame_id = "laser";
  const sensor_msgs::LaserScan msg = ToLaserScanMsg(laser, header);
  EXPECT_EQ(msg.header.frame_id, "laser");
  EXPECT_FLOAT_EQ(msg.angle_max, static_cast<float>(scan.angle_min + 359 * scan.angle_increment));
  EXPECT_EQ(msg.range_max, 12.0f);
  EXPECT_TRUE(msg.intensities.empty());
  const ImportedScan back = FromLaserScanMsg(msg);
  EXPECT_EQ(back.non_finite_ranges, 0u);
  EXPECT_EQ(back.scan.max_range, 12.0);
  EXPECT_NEAR(back.scan.angle_min, scan.angle_min, 1e-6);
  EXPECT_NEAR(back.scan.angle_increment, scan.angle_increment, 1e-8);
  ASSERT_EQ(back.scan.ranges.size(), 360u);
  for (std::size_t i = 0; i < 360; ++i) {
    EXPECT_EQ(static_cast<float>(back.scan.ranges[i]), static_cast<float>(scan.ranges[i]));
  }
  EXPECT_EQ(back.scan.ranges[7], 12.0);
}

TEST(RosScanTest, NonFiniteReadingsAreNoReturns) {
  sensor_msgs::LaserScan msg;
  msg.range_max = 5.5f;
  msg.ranges = {1.0f, std::numeric_limits<float>::quiet_NaN(),
                std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()};
  msg.intensities = {10.0f, 20.0f, 30.0f, 40.0f};
  const ImportedScan scan = FromLaserScanMsg(msg);
  EXPECT_EQ(scan.non_finite_ranges, 3u);
  EXPECT_EQ(scan.scan.ranges, (std::vector<double>{1.0, 5.5, 5.5, 5.5}));
  EXPECT_EQ(scan.intensities, (std::vector<double>{10.0, 20.0, 30.0, 40.0}));
}

}  // namespace
}  // namespace semchain::ros1
