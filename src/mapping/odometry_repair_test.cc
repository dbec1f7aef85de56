#include "mapping/odometry_repair.h"

#include <gtest/gtest.h>

namespace semchain::mapping {
namespace {

carmen::Odometry Record(double time, double tv) {
  carmen::Odometry record;
  record.tv = tv;
  record.stamp.timestamp = time;
  return record;
}

// A robot at heading π/2 that drives 0.1 m forward per scan for three scans, then backs up
// 0.1 m per scan for three, logged by a base that integrated |v|: the logged pose keeps moving
// forward. The laser sits 0.2 m ahead of the robot.
std::vector<StampedScan> ForwardThenBackLoggedAsForward() {
  std::vector<StampedScan> scans;
  const Pose2 laser_offset(0.2, 0.0, 0.0);
  for (int i = 0; i <= 6; ++i) {
    StampedScan scan;
    scan.scan.timestamp = 1.0 * i;
    scan.odometry = Pose2(5.0, 2.0 + 0.1 * i, 1.5707963267948966);
    scan.laser_pose = scan.odometry * laser_offset;
    scans.push_back(scan);
  }
  return scans;
}

TEST(OdometryRepairTest, StepsThatContradictTheVelocityAreReversed) {
  std::vector<StampedScan> scans = ForwardThenBackLoggedAsForward();
  std::vector<carmen::Odometry> records;
  for (int i = 0; i <= 12; ++i) records.push_back(Record(0.5 * i, i <= 6 ? 0.1 : -0.1));
  std::vector<const carmen::Odometry*> pointers;
  for (const carmen::Odometry& r : records) pointers.push_back(&r);
  const ReversedOdometryRepair repair = RepairReversedOdometry(pointers, &scans);
  EXPECT_EQ(repair.steps, 3);
  EXPECT_NEAR(repair.meters, 0.3, 1e-9);
  // Up to 0.3 m forward, then back to where it started; heading and laser offset unchanged.
  const double expected_y[] = {2.0, 2.1, 2.2, 2.3, 2.2, 2.1, 2.0};
  for (int i = 0; i <= 6; ++i) {
    EXPECT_NEAR(scans[i].odometry.x, 5.0, 1e-9) << i;
    EXPECT_NEAR(scans[i].odometry.y, expected_y[i], 1e-9) << i;
    EXPECT_NEAR(scans[i].laser_pose.y, expected_y[i] + 0.2, 1e-9) << i;
  }
}

TEST(OdometryRepairTest, ConsistentOrMissingVelocitiesLeaveTheLogAsWritten) {
  const std::vector<StampedScan> logged = ForwardThenBackLoggedAsForward();
  std::vector<carmen::Odometry> records;
  for (int i = 0; i <= 12; ++i) records.push_back(Record(0.5 * i, 0.1));
  std::vector<const carmen::Odometry*> pointers;
  for (const carmen::Odometry& r : records) pointers.push_back(&r);
  for (const bool with_records : {true, false}) {
    std::vector<StampedScan> scans = logged;
    const ReversedOdometryRepair repair = RepairReversedOdometry(
        with_records ? pointers : std::vector<const carmen::Odometry*>{}, &scans);
    EXPECT_EQ(repair.steps, 0);
    for (std::size_t i = 0; i < scans.size(); ++i) {
      // Bit for bit: a log without the fault must give the same SLAM output as before.
      EXPECT_EQ(scans[i].odometry.y, logged[i].odometry.y);
      EXPECT_EQ(scans[i].laser_pose.theta, logged[i].laser_pose.theta);
    }
  }
}

}  // namespace
}  // namespace semchain::mapping
