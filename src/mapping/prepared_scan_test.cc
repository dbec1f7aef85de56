#include "mapping/prepared_scan.h"

#include <gtest/gtest.h>

#include "core/angles.h"
#include "mapping/required_matches.h"

namespace semchain::mapping {
namespace {

// 361 beams over 360°: 'returns' at 3 m, 'no_echo' at the sensor's max range, the rest zero.
LaserScan MixedScan(int returns, int no_echo) {
  LaserScan scan;
  scan.angle_min = -kPi;
  scan.angle_increment = 2.0 * kPi / 361.0;
  scan.max_range = 81.91;
  scan.ranges.assign(361, 0.0);
  for (int i = 0; i < returns; ++i) scan.ranges[static_cast<std::size_t>(i)] = 3.0;
  for (int i = returns; i < returns + no_echo; ++i) {
    scan.ranges[static_cast<std::size_t>(i)] = scan.max_range;
  }
  return scan;
}

// In open space a scan measures with every beam: its few near returns must match the full count.
TEST(PreparedScanTest, OpenSpaceCountsEveryMeasuredReading) {
  const PreparedScan scan = PrepareScan(MixedScan(40, 300), Pose2(), {});
  EXPECT_EQ(scan.measured, 340);
  const MatchPoints points = SelectMatchPoints(scan, 20.0);
  EXPECT_EQ(points.size(), 40u);
  EXPECT_EQ(points.measured, 340);
  EXPECT_EQ(RequiredMatches(30, points.measured), 30);
  // Every second beam: half the readings.
  EXPECT_EQ(SelectMatchPoints(scan, 20.0, 2).measured, 170);
}

// A sensor that measured nothing with most of its beams (zero readings, a Neato) needs a third of
// the returns it has.
TEST(PreparedScanTest, ZeroReadingsAreNotMeasurements) {
  const PreparedScan scan = PrepareScan(MixedScan(60, 0), Pose2(), {});
  EXPECT_EQ(scan.measured, 60);
  const MatchPoints points = SelectMatchPoints(scan, 20.0);
  EXPECT_EQ(points.measured, 60);
  EXPECT_EQ(RequiredMatches(30, points.measured), 20);
}

// A scan put together by hand, without its readings counted, counts its returns.
TEST(PreparedScanTest, WithoutACountTheReturnsAreTheMeasurements) {
  PreparedScan scan;
  for (int i = 0; i < 12; ++i) {
    scan.beams.push_back({Eigen::Vector2d(1.0, 0.1 * i), Eigen::Vector2d(1.0, 0.0), true});
  }
  EXPECT_EQ(SelectMatchPoints(scan, 20.0).measured, 12);
  EXPECT_EQ(RequiredMatches(30, 12), 4);
  EXPECT_EQ(RequiredMatches(0, 12), 0);
}

}  // namespace
}  // namespace semchain::mapping
