// `bag import` on bags as a robot records them, written here message by message: odometry
// interpolated from tf or taken from /odom, NaN readings, and the errors a user can cause.
#include "ros/bag_import.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/LaserScan.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>

#include "core/atomic_file.h"
#include "io/carmen.h"
#include "ros/bag_writer.h"
#include "ros/ros_geometry.h"

namespace semchain::ros1 {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class BagImportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("semchain_bag_import_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    options_.show_progress = false;
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Writes dir_/in.bag with 'fill'.
  fs::path WriteBag(const std::function<void(BagWriter&)>& fill) {
    Result<std::unique_ptr<BagWriter>> bag =
        BagWriter::Create(dir_ / "in.bag", BagCompression::kNone);
    EXPECT_TRUE(bag.ok());
    fill(**bag);
    EXPECT_TRUE((*bag)->Finish().ok());
    return dir_ / "in.bag";
  }

  Result<BagImportSummary> Import() {
    return ImportBagToRun(dir_ / "in.bag", dir_ / "run", options_);
  }

  fs::path dir_;
  BagImportOptions options_;
};

ros::Time At(double seconds) { return ros::Time(seconds); }

sensor_msgs::LaserScan Scan(double seconds, const std::string& frame = "laser") {
  sensor_msgs::LaserScan scan;
  scan.header.stamp = At(seconds);
  scan.header.frame_id = frame;
  scan.angle_min = -1.5f;
  scan.angle_increment = 0.5f;
  scan.angle_max = 1.5f;
  scan.range_max = 8.0f;
  scan.ranges = {1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f};
  return scan;
}

tf2_msgs::TFMessage Tf(double seconds, const std::string& parent, const std::string& child,
                       const Pose2& pose) {
  geometry_msgs::TransformStamped transform;
  transform.header.stamp = At(seconds);
  transform.header.frame_id = parent;
  transform.child_frame_id = child;
  transform.transform = ToTransformMsg(pose);
  tf2_msgs::TFMessage msg;
  msg.transforms.push_back(transform);
  return msg;
}

void WriteLaserMount(BagWriter& bag) {
  ASSERT_TRUE(
      bag.Write("/tf_static", At(1.0), Tf(1.0, "base_link", "laser", Pose2(0.2, 0, 0)), true).ok());
}

TEST_F(BagImportTest, InterpolatesTfOdometryAtTheScanStamps) {
  WriteBag([](BagWriter& bag) {
    WriteLaserMount(bag);
    // Odometry at 10 Hz, scans between: the robot drives along x at 1 m/s, turning 1 rad/s.
    for (int i = 0; i <= 10; ++i) {
      const double t = 1.0 + 0.1 * i;
      ASSERT_TRUE(
          bag.Write("/tf", At(t), Tf(t, "odom", "base_link", Pose2(0.1 * i, 0.0, 0.1 * i))).ok());
    }
    for (const double t : {0.95, 1.25, 1.55, 2.05})
      ASSERT_TRUE(bag.Write("/scan", At(t), Scan(t)).ok());
  });
  const Result<BagImportSummary> summary = Import();
  ASSERT_TRUE(summary.ok()) << summary.status().message();
  EXPECT_EQ(summary->scans, 2u);
  EXPECT_EQ(summary->skipped_scans, 2u);  // before the first and after the last odometry
  ASSERT_EQ(summary->warnings.size(), 1u);
  EXPECT_THAT(summary->warnings[0], HasSubstr("2 scans on /scan left out"));
  const Result<carmen::Log> log = carmen::ReadLog(dir_ / "run/log.clf");
  ASSERT_TRUE(log.ok()) << log.status().message();
  const auto lasers = log->Lasers();
  ASSERT_EQ(lasers.size(), 2u);
  EXPECT_DOUBLE_EQ(lasers[0]->stamp.timestamp, 1.25);
  EXPECT_NEAR(lasers[0]->scan.odometry.x, 0.25, 1e-9);
  EXPECT_NEAR(lasers[0]->scan.odometry.theta, 0.25, 1e-9);
  EXPECT_NEAR(lasers[1]->scan.odometry.x, 0.55, 1e-9);
  // The laser sits 0.2 m ahead of base_link, turned with the robot.
  const Pose2 laser = lasers[1]->scan.LaserOffset();
  EXPECT_NEAR(laser.x, 0.2, 1e-9);
  EXPECT_NEAR(laser.y, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(lasers[1]->scan.scan.angle_min, -1.5);
  EXPECT_DOUBLE_EQ(lasers[1]->scan.scan.max_range, 8.0);
  EXPECT_EQ(lasers[1]->scan.scan.ranges[6], 7.0);
}

TEST_F(BagImportTest, TakesOdometryFromTheOdomTopicWithoutTf) {
  WriteBag([](BagWriter& bag) {
    WriteLaserMount(bag);
    for (int i = 0; i <= 4; ++i) {
      const double t = 1.0 + 0.5 * i;
      nav_msgs::Odometry odom;
      odom.header.stamp = At(t);
      odom.header.frame_id = "odom";
      odom.child_frame_id = "base_link";
      odom.pose.pose = ToPoseMsg(Pose2(0.0, 0.5 * i, 0.0));
      odom.twist.twist.linear.x = 0.5;
      ASSERT_TRUE(bag.Write("/odom", At(t), odom).ok());
    }
    for (const double t : {1.5, 1.75})
      ASSERT_TRUE(bag.Write("/scan", At(t), Scan(t, "/laser")).ok());
  });
  const Result<BagImportSummary> summary = Import();
  ASSERT_TRUE(summary.ok()) << summary.status().message();
  EXPECT_EQ(summary->odometry, "/odom");
  const Result<carmen::Log> log = carmen::ReadLog(dir_ / "run/log.clf");
  ASSERT_TRUE(log.ok());
  const auto lasers = log->Lasers();
  ASSERT_EQ(lasers.size(), 2u);
  EXPECT_NEAR(lasers[0]->scan.odometry.y, 0.5, 1e-9);
  EXPECT_NEAR(lasers[1]->scan.odometry.y, 0.75, 1e-9);
  EXPECT_EQ(lasers[0]->tv, 0.5);  // the twist of the /odom message at the scan's stamp
  EXPECT_EQ(lasers[1]->tv, 0.0);  // none at 1.75 s
}

TEST_F(BagImportTest, StoresNonFiniteReadingsAsMaxRange) {
  WriteBag([](BagWriter& bag) {
    WriteLaserMount(bag);
    for (const double t : {1.0, 2.0}) {
      ASSERT_TRUE(bag.Write("/tf", At(t), Tf(t, "odom", "base_link", Pose2())).ok());
    }
    sensor_msgs::LaserScan scan = Scan(1.5);
    scan.ranges[1] = std::numeric_limits<float>::quiet_NaN();
    scan.ranges[2] = std::numeric_limits<float>::infinity();
    scan.ranges[3] = -std::numeric_limits<float>::infinity();
    ASSERT_TRUE(bag.Write("/scan", At(1.5), scan).ok());
  });
  const Result<BagImportSummary> summary = Import();
  ASSERT_TRUE(summary.ok()) << summary.status().message();
  EXPECT_EQ(summary->non_finite_ranges, 3u);
  const Result<carmen::Log> log = carmen::ReadLog(dir_ / "run/log.clf");
  ASSERT_TRUE(log.ok()) << log.status().message();
  const std::vector<double>& ranges = log->Lasers()[0]->scan.scan.ranges;
  EXPECT_EQ(ranges, (std::vector<double>{1.0, 8.0, 8.0, 8.0, 5.0, 6.0, 7.0}));
}

TEST_F(BagImportTest, ABagWithoutScansNamesTheTopicsItHas) {
  WriteBag([](BagWriter& bag) {
    std_msgs::String chatter;
    chatter.data = "hello";
    ASSERT_TRUE(bag.Write("/chatter", At(1.0), chatter).ok());
    ASSERT_TRUE(bag.Write("/tf", At(1.0), Tf(1.0, "odom", "base_link", Pose2())).ok());
  });
  const Result<BagImportSummary> summary = Import();
  ASSERT_FALSE(summary.ok());
  EXPECT_THAT(summary.status().message(), HasSubstr("no topic /scan (sensor_msgs/LaserScan)"));
  EXPECT_THAT(summary.status().message(), HasSubstr("/chatter (std_msgs/String, 1 messages)"));
  EXPECT_THAT(summary.status().message(), HasSubstr("/tf (tf2_msgs/TFMessage, 1 messages)"));
  EXPECT_FALSE(fs::exists(dir_ / "run"));
}

TEST_F(BagImportTest, AnotherScanTopicCanBeNamed) {
  WriteBag([](BagWriter& bag) {
    WriteLaserMount(bag);
    for (const double t : {1.0, 2.0}) {
      ASSERT_TRUE(bag.Write("/tf", At(t), Tf(t, "odom", "base_link", Pose2())).ok());
    }
    ASSERT_TRUE(bag.Write("/front/scan", At(1.5), Scan(1.5)).ok());
  });
  options_.topics.scan = "/front/scan";
  const Result<BagImportSummary> summary = Import();
  ASSERT_TRUE(summary.ok()) << summary.status().message();
  EXPECT_EQ(summary->scans, 1u);
}

TEST_F(BagImportTest, NoOdometryIsAnErrorNamingTheTfFrames) {
  WriteBag([](BagWriter& bag) {
    WriteLaserMount(bag);
    ASSERT_TRUE(bag.Write("/scan", At(1.5), Scan(1.5)).ok());
  });
  const Result<BagImportSummary> summary = Import();
  ASSERT_FALSE(summary.ok());
  EXPECT_THAT(summary.status().message(),
              HasSubstr("no odometry: tf has no transform odom -> base_link (tf frames: "
                        "base_link, laser)"));
}

TEST_F(BagImportTest, ATiltedLaserIsAnError) {
  WriteBag([](BagWriter& bag) {
    Eigen::Isometry3d upside_down = Eigen::Isometry3d::Identity();
    upside_down.linear() = Eigen::AngleAxisd(3.14159, Eigen::Vector3d::UnitX()).toRotationMatrix();
    tf2_msgs::TFMessage mount = Tf(1.0, "base_link", "laser", Pose2());
    mount.transforms[0].transform = ToTransformMsg(upside_down);
    ASSERT_TRUE(bag.Write("/tf_static", At(1.0), mount, true).ok());
    for (const double t : {1.0, 2.0}) {
      ASSERT_TRUE(bag.Write("/tf", At(t), Tf(t, "odom", "base_link", Pose2())).ok());
    }
    ASSERT_TRUE(bag.Write("/scan", At(1.5), Scan(1.5)).ok());
  });
  const Result<BagImportSummary> summary = Import();
  ASSERT_FALSE(summary.ok());
  EXPECT_THAT(summary.status().message(), HasSubstr("a 2D log needs a level laser"));
}

TEST_F(BagImportTest, AFileThatIsNotABagIsAnError) {
  ASSERT_TRUE(WriteFileAtomically(dir_ / "in.bag", "not a bag at all\n").ok());
  const Result<BagImportSummary> summary = Import();
  ASSERT_FALSE(summary.ok());
  EXPECT_THAT(summary.status().message(), HasSubstr("in.bag: not a readable ROS bag"));
  EXPECT_THAT(ImportBagToRun(dir_ / "missing.bag", dir_ / "run", options_).status().message(),
              HasSubstr("missing.bag: no such bag file"));
}

}  // namespace
}  // namespace semchain::ros1
