#include "sim/simulator.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "core/atomic_file.h"
#include "io/carmen.h"
#include "io/detections_io.h"
#include "io/trajectory_io.h"
#include "sim/lidar.h"

namespace semchain::sim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// A 6 m × 4 m room with a cabinet and a short route; a small, noiseless lidar keeps it fast.
World TinyWorld() {
  World world;
  world.name = "tiny";
  world.walls = {{{0, 0}, {6, 0}, {6, 4}, {0, 4}, {0, 0}}};
  Solid cabinet;
  cabinet.class_name = "cabinet";
  cabinet.footprint.center = {4.0, 3.6};
  cabinet.footprint.width = 0.8;
  cabinet.footprint.depth = 0.5;
  cabinet.height = 1.2;
  world.objects.push_back(cabinet);
  world.classes = DefaultClassNames();
  world.robot.start = Pose2(1.0, 1.0, 0.0);
  world.robot.lidar.beams = 90;
  world.robot.lidar.noise_std = 0.0;
  world.robot.camera.width = 80;
  world.robot.camera.height_px = 60;
  world.mapping_route = {{2.0, 1.0}, {2.0, 2.0}};
  return world;
}

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() /
                       ("semchain_simulator_test_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  return dir;
}

TEST(SimulatorTest, WritesAConsistentRunWithoutFrames) {
  const World world = TinyWorld();
  SimulationOptions options;
  options.seed = 3;
  options.write_frames = false;
  options.show_progress = false;
  const fs::path run = FreshDir("no_frames");
  ASSERT_TRUE(Simulate(world, options, run).ok());
  EXPECT_FALSE(fs::exists(run / "frames"));
  EXPECT_FALSE(fs::exists(run / "detections.jsonl"));
  EXPECT_TRUE(fs::exists(run / "camera.yaml"));
  EXPECT_TRUE(fs::exists(run / "run.yaml"));

  const auto log = carmen::ReadLog(run / "log.clf");
  ASSERT_TRUE(log.ok()) << log.status().message();
  const auto truth = ReadTrajectory(run / "truth.txt");
  ASSERT_TRUE(truth.ok()) << truth.status().message();
  const auto lasers = log->Lasers();
  const auto odometry = log->Odometries();
  const auto true_poses = log->TruePoses();
  ASSERT_GT(lasers.size(), 20u);
  ASSERT_EQ(lasers.size(), truth->size());
  ASSERT_EQ(odometry.size(), truth->size());
  ASSERT_EQ(true_poses.size(), truth->size());
  // Odometry starts at the true start pose; the noiseless lidar matches a scan from the truth.
  EXPECT_DOUBLE_EQ(odometry.front()->pose.x, 1.0);
  EXPECT_DOUBLE_EQ(odometry.front()->pose.y, 1.0);
  const Scene scene(world);
  Rng rng = MakeRng(0);
  for (std::size_t i = 0; i < truth->size(); i += 7) {
    EXPECT_DOUBLE_EQ(lasers[i]->stamp.timestamp, (*truth)[i].timestamp);
    EXPECT_NEAR(true_poses[i]->truth.x, (*truth)[i].pose.x, 1e-9);
    const LaserScan expected =
        SimulateScan(scene, world.robot.lidar, (*truth)[i].pose, (*truth)[i].timestamp, rng);
    const LaserScan& logged = lasers[i]->scan.scan;
    ASSERT_EQ(logged.size(), 90u);
    EXPECT_NEAR(logged.angle_min, expected.angle_min, 1e-9);
    EXPECT_NEAR(logged.angle_increment, expected.angle_increment, 1e-9);
    for (std::size_t b = 0; b < logged.size(); ++b) {
      EXPECT_NEAR(logged.ranges[b], expected.ranges[b], 1e-6) << "scan " << i << " beam " << b;
    }
  }
  // The last true pose is the last waypoint.
  EXPECT_NEAR(truth->back().pose.x, 2.0, 0.021);
  EXPECT_NEAR(truth->back().pose.y, 2.0, 0.021);
  fs::remove_all(run);
}

TEST(SimulatorTest, WritesFramesAndDetectionsAtTheCameraRate) {
  World world = TinyWorld();
  world.robot.frame_rate_hz = 2.0;
  SimulationOptions options;
  options.show_progress = false;
  const fs::path run = FreshDir("frames");
  ASSERT_TRUE(Simulate(world, options, run).ok());
  const auto truth = ReadTrajectory(run / "truth.txt");
  ASSERT_TRUE(truth.ok());
  const auto detections = ReadDetectionsJsonl(run / "detections.jsonl");
  ASSERT_TRUE(detections.ok()) << detections.status().message();
  const double duration = truth->back().timestamp;
  EXPECT_EQ(detections->size(), static_cast<std::size_t>(std::floor(duration * 2.0 + 1e-6)) + 1);
  for (std::size_t i = 0; i < detections->size(); ++i) {
    const FrameDetections& frame = (*detections)[i];
    EXPECT_NEAR(frame.stamp, 0.5 * static_cast<double>(i), 1e-9);
    const cv::Mat rgb = cv::imread((run / (frame.frame + ".png")).string(), cv::IMREAD_UNCHANGED);
    const cv::Mat depth =
        cv::imread((run / (frame.frame + "_depth.png")).string(), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(rgb.empty()) << frame.frame;
    EXPECT_EQ(rgb.type(), CV_8UC3);
    EXPECT_EQ(rgb.cols, 80);
    EXPECT_EQ(depth.type(), CV_16UC1);
  }
  EXPECT_EQ((*detections)[1].frame, "frames/000001");
  fs::remove_all(run);
}

TEST(SimulatorTest, RefusesToOverwriteWhatIsNotARun) {
  const World world = TinyWorld();
  SimulationOptions options;
  options.write_frames = false;
  options.show_progress = false;
  const fs::path file = FreshDir("a_file");
  ASSERT_TRUE(WriteFileAtomically(file, "not a run").ok());
  EXPECT_THAT(Simulate(world, options, file).message(), HasSubstr("not a directory"));
  fs::remove(file);
  const fs::path foreign = FreshDir("foreign");
  fs::create_directories(foreign);
  ASSERT_TRUE(WriteFileAtomically(foreign / "thesis.tex", "precious").ok());
  EXPECT_THAT(Simulate(world, options, foreign).message(), HasSubstr("not empty"));
  EXPECT_TRUE(fs::exists(foreign / "thesis.tex"));
  fs::remove_all(foreign);
}

TEST(SimulatorTest, ReplacesAnEarlierRunAndLeavesNothingOnFailure) {
  World world = TinyWorld();
  SimulationOptions options;
  options.write_frames = false;
  options.show_progress = false;
  const fs::path run = FreshDir("replace");
  ASSERT_TRUE(Simulate(world, options, run / "").ok());  // a trailing slash is fine
  const auto before = ReadFile(run / "log.clf");
  options.seed = 99;
  world.robot.lidar.noise_std = 0.01;
  ASSERT_TRUE(Simulate(world, options, run).ok());
  EXPECT_NE(*ReadFile(run / "log.clf"), *before);
  // A route into a wall fails before anything is written.
  world.mapping_route = {{8.0, 1.0}};
  const fs::path failed = FreshDir("failed");
  EXPECT_THAT(Simulate(world, options, failed).message(), HasSubstr("hits a surface"));
  EXPECT_FALSE(fs::exists(failed));
  for (const auto& entry : fs::directory_iterator(fs::temp_directory_path())) {
    EXPECT_THAT(entry.path().filename().string(),
                ::testing::Not(HasSubstr(failed.filename().string() + ".partial")));
  }
  fs::remove_all(run);
}

}  // namespace
}  // namespace semchain::sim
