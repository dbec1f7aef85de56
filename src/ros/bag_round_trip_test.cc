// A simulated run → `bag export` → `bag import` gives back the same run: the same scans (ranges
// bit for bit at the bag's float precision), odometry, truth, camera, frames and detections.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <variant>
#include <vector>

#include "core/angles.h"
#include "core/atomic_file.h"
#include "io/camera_io.h"
#include "io/carmen.h"
#include "io/detections_io.h"
#include "io/trajectory_io.h"
#include "ros/bag_export.h"
#include "ros/bag_import.h"
#include "ros/bag_reader.h"
#include "ros/ros_scan.h"
#include "sim/simulator.h"
#include "sim/world.h"

namespace semchain::ros1 {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path TestDir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("semchain_bag_test_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Room A of the bundled world: the robot faces the cabinet and drives 0.5 m towards it, about
// 20 scans and 4 camera frames.
fs::path SimulateShortRun(const fs::path& dir) {
  const fs::path world_path = fs::path(SEMCHAIN_SOURCE_DIR) / "worlds/two_similar_rooms.yaml";
  Result<sim::World> world = sim::LoadWorld(world_path);
  EXPECT_TRUE(world.ok()) << world.status().message();
  sim::SimulationOptions options;
  options.seed = 5;
  options.show_progress = false;
  options.start = Pose2(3.0, 4.0, std::numbers::pi / 2.0);
  options.route.kind = sim::RouteSpec::Kind::kWaypoints;
  options.route.waypoints = {{3.0, 4.5}};
  options.world_yaml = *ReadFile(world_path);
  const fs::path run = dir / "run";
  const Status status = sim::Simulate(*world, options, run);
  EXPECT_TRUE(status.ok()) << status.message();
  return run;
}

BagExportOptions ExportOptions(bool images) {
  BagExportOptions options;
  options.show_progress = false;
  options.images = images;
  return options;
}

BagImportOptions ImportOptions() {
  BagImportOptions options;
  options.show_progress = false;
  return options;
}

void ExpectSamePose(const Pose2& a, const Pose2& b, const std::string& what) {
  EXPECT_NEAR(a.x, b.x, 1e-9) << what;
  EXPECT_NEAR(a.y, b.y, 1e-9) << what;
  EXPECT_NEAR(AngleDifference(a.theta, b.theta), 0.0, 1e-9) << what;
}

void ExpectSameLog(const fs::path& original, const fs::path& imported) {
  const Result<carmen::Log> a = carmen::ReadLog(original / "log.clf");
  const Result<carmen::Log> b = carmen::ReadLog(imported / "log.clf");
  ASSERT_TRUE(a.ok() && b.ok());
  const auto lasers_a = a->Lasers();
  const auto lasers_b = b->Lasers();
  ASSERT_EQ(lasers_a.size(), lasers_b.size());
  ASSERT_GT(lasers_a.size(), 10u);
  for (std::size_t i = 0; i < lasers_a.size(); ++i) {
    const carmen::Laser& la = *lasers_a[i];
    const carmen::Laser& lb = *lasers_b[i];
    const std::string what = "scan " + std::to_string(i);
    EXPECT_NEAR(la.stamp.timestamp, lb.stamp.timestamp, 1e-9) << what;
    EXPECT_EQ(lb.kind, carmen::Laser::Kind::kRobotLaser1);
    ExpectSamePose(la.scan.odometry, lb.scan.odometry, what + " odometry");
    ExpectSamePose(la.scan.laser_pose, lb.scan.laser_pose, what + " laser pose");
    EXPECT_EQ(la.tv, lb.tv) << what;
    EXPECT_EQ(la.rv, lb.rv) << what;
    const LaserScan& sa = la.scan.scan;
    const LaserScan& sb = lb.scan.scan;
    EXPECT_NEAR(sa.angle_min, sb.angle_min, 1e-6) << what;
    EXPECT_NEAR(sa.angle_increment, sb.angle_increment, 1e-7) << what;
    EXPECT_EQ(sa.max_range, sb.max_range) << what;
    ASSERT_EQ(sa.size(), sb.size()) << what;
    for (std::size_t k = 0; k < sa.size(); ++k) {
      // The bag holds float32 ranges: the same float, written as its shortest decimal.
      ASSERT_EQ(static_cast<float>(sa.ranges[k]), static_cast<float>(sb.ranges[k])) << what;
      ASSERT_EQ(sb.ranges[k], ShortestDouble(static_cast<float>(sa.ranges[k]))) << what;
    }
  }
  const auto odometry_a = a->Odometries();
  const auto odometry_b = b->Odometries();
  ASSERT_EQ(odometry_a.size(), odometry_b.size());
  for (std::size_t i = 0; i < odometry_a.size(); ++i) {
    ExpectSamePose(odometry_a[i]->pose, odometry_b[i]->pose, "ODOM " + std::to_string(i));
  }
  const auto truth_a = a->TruePoses();
  const auto truth_b = b->TruePoses();
  ASSERT_EQ(truth_a.size(), truth_b.size());
  for (std::size_t i = 0; i < truth_a.size(); ++i) {
    ExpectSamePose(truth_a[i]->truth, truth_b[i]->truth, "TRUEPOS " + std::to_string(i));
  }
}

void ExpectSameTruth(const fs::path& original, const fs::path& imported) {
  const auto a = ReadTrajectory(original / "truth.txt");
  const auto b = ReadTrajectory(imported / "truth.txt");
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_EQ(a->size(), b->size());
  for (std::size_t i = 0; i < a->size(); ++i) {
    EXPECT_NEAR((*a)[i].timestamp, (*b)[i].timestamp, 1e-9);
    ExpectSamePose((*a)[i].pose, (*b)[i].pose, "truth " + std::to_string(i));
  }
}

void ExpectSameCamera(const fs::path& original, const fs::path& imported) {
  const Result<CameraInfo> a = ReadCameraYaml(original / "camera.yaml");
  const Result<CameraInfo> b = ReadCameraYaml(imported / "camera.yaml");
  ASSERT_TRUE(a.ok() && b.ok());
  const PinholeCamera& ka = a->camera.intrinsics;
  const PinholeCamera& kb = b->camera.intrinsics;
  EXPECT_EQ(ka.width, kb.width);
  EXPECT_EQ(ka.height, kb.height);
  EXPECT_EQ(ka.fx, kb.fx);
  EXPECT_EQ(ka.fy, kb.fy);
  EXPECT_EQ(ka.cx, kb.cx);
  EXPECT_EQ(ka.cy, kb.cy);
  EXPECT_EQ(a->camera.max_range, b->camera.max_range);
  EXPECT_EQ(a->depth_scale, b->depth_scale);
  EXPECT_EQ(a->frame_rate_hz, b->frame_rate_hz);
  EXPECT_TRUE(a->camera.robot_from_camera.isApprox(b->camera.robot_from_camera, 1e-12));
  // The same file, to the digit.
  EXPECT_EQ(*ReadFile(original / "camera.yaml"), *ReadFile(imported / "camera.yaml"));
}

void ExpectSameDetections(const fs::path& original, const fs::path& imported, bool images) {
  const auto a = ReadDetectionsJsonl(original / "detections.jsonl");
  const auto b = ReadDetectionsJsonl(imported / "detections.jsonl");
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_EQ(a->size(), b->size());
  ASSERT_GE(a->size(), 3u);
  std::size_t detections = 0;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const FrameDetections& fa = (*a)[i];
    const FrameDetections& fb = (*b)[i];
    EXPECT_EQ(fa.frame, fb.frame);
    EXPECT_NEAR(fa.stamp, fb.stamp, 1e-9);
    ASSERT_EQ(fa.detections.size(), fb.detections.size());
    for (std::size_t k = 0; k < fa.detections.size(); ++k) {
      const Detection& da = fa.detections[k];
      const Detection& db = fb.detections[k];
      EXPECT_EQ(da.class_name, db.class_name);
      EXPECT_EQ(da.class_id, db.class_id);
      EXPECT_EQ(da.score, db.score);
      EXPECT_EQ(da.depth_m, db.depth_m);
      for (int c = 0; c < 4; ++c) EXPECT_EQ(da.box[c], db.box[c]);
    }
    detections += fa.detections.size();
    if (images) {
      // The simulator's PNG encoder wrote both: the same pixels give the same bytes.
      for (const std::string suffix : {".png", "_depth.png"}) {
        EXPECT_EQ(*ReadFile(original / (fa.frame + suffix)),
                  *ReadFile(imported / (fb.frame + suffix)))
            << fa.frame << suffix;
      }
    }
  }
  EXPECT_GT(detections, 0u) << "the route should see the cabinet";
}

TEST(BagRoundTripTest, ExportThenImportGivesBackTheRun) {
  const fs::path dir = TestDir("round_trip");
  const fs::path run = SimulateShortRun(dir);
  const BagExportOptions export_options = ExportOptions(true);
  const Result<BagExportSummary> exported = ExportRunToBag(run, dir / "run.bag", export_options);
  ASSERT_TRUE(exported.ok()) << exported.status().message();
  EXPECT_EQ(exported->stamp_offset_seconds, 1);  // the simulator's clock starts at 0
  EXPECT_EQ(exported->images, 2 * exported->frames);

  const BagImportOptions import_options = ImportOptions();
  const Result<BagImportSummary> imported =
      ImportBagToRun(dir / "run.bag", dir / "imported", import_options);
  ASSERT_TRUE(imported.ok()) << imported.status().message();
  EXPECT_TRUE(imported->warnings.empty()) << imported->warnings.front();
  EXPECT_EQ(imported->scans, exported->scans);
  EXPECT_EQ(imported->frames, exported->frames);
  EXPECT_EQ(imported->odometry, "tf odom -> base_link");

  ExpectSameLog(run, dir / "imported");
  ExpectSameTruth(run, dir / "imported");
  ExpectSameCamera(run, dir / "imported");
  ExpectSameDetections(run, dir / "imported", true);
  EXPECT_EQ(*ReadFile(run / "world.yaml"), *ReadFile(dir / "imported/world.yaml"));
  EXPECT_TRUE(fs::exists(dir / "imported/run.yaml"));
  EXPECT_FALSE(fs::exists(dir / ("imported.partial." + std::to_string(::getpid()))));

  // Once through a bag, a run's scans go through again unchanged, double for double.
  ASSERT_TRUE(ExportRunToBag(dir / "imported", dir / "again.bag", export_options).ok());
  ASSERT_TRUE(ImportBagToRun(dir / "again.bag", dir / "again", import_options).ok());
  const Result<carmen::Log> once = carmen::ReadLog(dir / "imported/log.clf");
  const Result<carmen::Log> twice = carmen::ReadLog(dir / "again/log.clf");
  ASSERT_TRUE(once.ok() && twice.ok());
  ASSERT_EQ(once->Lasers().size(), twice->Lasers().size());
  for (std::size_t i = 0; i < once->Lasers().size(); ++i) {
    EXPECT_EQ(once->Lasers()[i]->scan.scan.ranges, twice->Lasers()[i]->scan.scan.ranges);
    EXPECT_EQ(once->Lasers()[i]->stamp.timestamp, twice->Lasers()[i]->stamp.timestamp);
  }
  fs::remove_all(dir);
}

TEST(BagRoundTripTest, NoImagesKeepsDetectionsAndTheCamera) {
  const fs::path dir = TestDir("no_images");
  const fs::path run = SimulateShortRun(dir);
  const BagExportOptions export_options = ExportOptions(false);
  const Result<BagExportSummary> exported = ExportRunToBag(run, dir / "small.bag", export_options);
  ASSERT_TRUE(exported.ok()) << exported.status().message();
  EXPECT_EQ(exported->images, 0u);
  Result<std::unique_ptr<BagReader>> reader = BagReader::Open(dir / "small.bag");
  ASSERT_TRUE(reader.ok());
  EXPECT_FALSE((*reader)->Has("/camera/color/image_raw"));
  EXPECT_TRUE((*reader)->Has("/semchain/detections"));

  const BagImportOptions import_options = ImportOptions();
  ASSERT_TRUE(ImportBagToRun(dir / "small.bag", dir / "imported", import_options).ok());
  EXPECT_FALSE(fs::exists(dir / "imported/frames"));
  ExpectSameLog(run, dir / "imported");
  ExpectSameCamera(run, dir / "imported");
  ExpectSameDetections(run, dir / "imported", false);
  fs::remove_all(dir);
}

// A raw data set's log given as it is (a file, no run directory), whose clock steps back once
// (as the Intel log's does 631 times): the bag keeps the log's order, the scan stamped back
// going 1 ms after the one before it, and imports as the same scans and odometry.
TEST(BagRoundTripTest, ALogFileExportsInLogOrderWhenItsClockStepsBack) {
  const fs::path dir = TestDir("log_only");
  const fs::path run = SimulateShortRun(dir);
  Result<carmen::Log> log = carmen::ReadLog(run / "log.clf");
  ASSERT_TRUE(log.ok()) << log.status().message();
  std::vector<carmen::Laser> expected;
  for (const carmen::Laser* laser : log->Lasers()) expected.push_back(*laser);
  ASSERT_GT(expected.size(), 10u);
  // Scan 5 stamped 0.5 s before scan 4.
  std::size_t scan = 0;
  for (carmen::Record& record : log->records) {
    if (auto* laser = std::get_if<carmen::Laser>(&record); laser != nullptr && scan++ == 5) {
      laser->stamp.timestamp = expected[4].stamp.timestamp - 0.5;
    }
  }
  const fs::path log_path = dir / "raw.clf";
  ASSERT_TRUE(carmen::WriteLog(log_path, *log).ok());

  const Result<BagExportSummary> exported =
      ExportRunToBag(log_path, dir / "raw.bag", ExportOptions(false));
  ASSERT_TRUE(exported.ok()) << exported.status().message();
  EXPECT_EQ(exported->scans, expected.size());
  EXPECT_EQ(exported->frames, 0u);
  EXPECT_GE(exported->restamped_scans, 1u);
  const Result<BagImportSummary> imported =
      ImportBagToRun(dir / "raw.bag", dir / "imported", ImportOptions());
  ASSERT_TRUE(imported.ok()) << imported.status().message();
  const Result<carmen::Log> back = carmen::ReadLog(dir / "imported/log.clf");
  ASSERT_TRUE(back.ok());
  const auto back_lasers = back->Lasers();
  ASSERT_EQ(back_lasers.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const std::string what = "scan " + std::to_string(i);
    ExpectSamePose(expected[i].scan.odometry, back_lasers[i]->scan.odometry, what);
    EXPECT_EQ(static_cast<float>(expected[i].scan.scan.ranges[7]),
              static_cast<float>(back_lasers[i]->scan.scan.ranges[7]))
        << what;
    if (i > 0) {
      EXPECT_GT(back_lasers[i]->stamp.timestamp, back_lasers[i - 1]->stamp.timestamp) << what;
    }
  }
  EXPECT_NEAR(back_lasers[5]->stamp.timestamp, back_lasers[4]->stamp.timestamp + 1e-3, 1e-6);
  fs::remove_all(dir);
}

TEST(BagRoundTripTest, ImportRefusesADirectoryOfOtherThings) {
  const fs::path dir = TestDir("refuse");
  const fs::path run = SimulateShortRun(dir);
  const BagExportOptions export_options = ExportOptions(false);
  ASSERT_TRUE(ExportRunToBag(run, dir / "run.bag", export_options).ok());
  fs::create_directories(dir / "other");
  ASSERT_TRUE(WriteFileAtomically(dir / "other/notes.txt", "mine").ok());
  const BagImportOptions import_options = ImportOptions();
  const Result<BagImportSummary> imported =
      ImportBagToRun(dir / "run.bag", dir / "other", import_options);
  ASSERT_FALSE(imported.ok());
  EXPECT_THAT(imported.status().message(), HasSubstr("not empty"));
  EXPECT_TRUE(fs::exists(dir / "other/notes.txt"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace semchain::ros1
