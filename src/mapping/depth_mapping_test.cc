#include "mapping/depth_mapping.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "core/angles.h"
#include "core/transforms.h"
#include "io/detections_io.h"
#include "io/rgbd_frame_io.h"
#include "mapping/map_io.h"

namespace semchain::mapping {
namespace {

namespace fs = std::filesystem;

TEST(PoseAtStampTest, NearestPoseWithinTheTolerance) {
  const std::vector<StampedPose> trajectory = {
      {0.0, Pose2(0, 0, 0)}, {0.1, Pose2(1, 0, 0)}, {0.2, Pose2(2, 0, 0)}};
  EXPECT_DOUBLE_EQ(PoseAtStamp(trajectory, 0.1, 1e-3)->x, 1.0);
  EXPECT_DOUBLE_EQ(PoseAtStamp(trajectory, 0.1004, 1e-3)->x, 1.0);
  EXPECT_DOUBLE_EQ(PoseAtStamp(trajectory, 0.0, 1e-3)->x, 0.0);
  EXPECT_DOUBLE_EQ(PoseAtStamp(trajectory, 0.2, 1e-3)->x, 2.0);
  const Result<Pose2> between = PoseAtStamp(trajectory, 0.15, 1e-3);
  ASSERT_FALSE(between.ok());
  EXPECT_NE(between.status().message().find("stamp 0.150000 s is not covered"), std::string::npos)
      << between.status().message();
  EXPECT_FALSE(PoseAtStamp(trajectory, 5.0, 1e-3).ok());
  EXPECT_FALSE(PoseAtStamp({}, 0.0, 1e-3).ok());
}

// A run with two depth frames of a level camera facing a wall 2 m ahead (from two robot poses
// 0.5 m apart, so the wall is at x = 2.0 in the world both times): the depth grid has the wall
// at x = 2.0 and free space in front of it, and fused with an empty lidar grid it stays.
TEST(FuseDepthRunTest, WallInTheDepthFramesEntersTheGrid) {
  const fs::path run =
      fs::temp_directory_path() / ("semchain_depth_run_" + std::to_string(getpid()));
  fs::remove_all(run);
  fs::create_directories(run / "frames");
  CameraInfo info;
  info.camera.intrinsics = PinholeCamera::FromFov(64, 48, DegToRad(60.0));
  info.camera.robot_from_camera = RobotFromOpticalCamera(0.0, 0.0, 0.3, 0.0, 0.0);
  ASSERT_TRUE(WriteCameraYaml(run / "camera.yaml", info).ok());
  std::vector<FrameDetections> frames = {{"frames/000000", 1.0, {}}, {"frames/000001", 2.0, {}}};
  ASSERT_TRUE(WriteDetectionsJsonl(run / "detections.jsonl", frames).ok());
  const std::vector<double> wall_distance = {2.0, 1.5};
  for (std::size_t i = 0; i < 2; ++i) {
    // A plane perpendicular to the optical axis has the same depth at every pixel.
    const cv::Mat depth(48, 64, CV_16UC1, cv::Scalar(wall_distance[i] * 1000.0));
    ASSERT_TRUE(cv::imwrite(DepthImagePath(run, frames[i].frame).string(), depth));
  }
  const std::vector<StampedPose> trajectory = {{2.0, Pose2(0.5, 0.0, 0.0)},
                                               {1.0, Pose2(0.0, 0.0, 0.0)}};  // any order
  const Result<DepthRun> depth_run = LoadDepthRun(run);
  ASSERT_TRUE(depth_run.ok()) << depth_run.status().message();
  const OccupancyGrid lidar;
  const Result<DepthFusionResult> result = FuseDepthRun(*depth_run, lidar, trajectory);
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_EQ(result->frames, 2u);
  const auto probability = [](const OccupancyGrid& grid, double x, double y) {
    return LogOddsToProbability(grid.LogOdds(grid.CellOf({x, y})));
  };
  for (const OccupancyGrid* grid : {&result->depth, &result->fused}) {
    EXPECT_GT(probability(*grid, 2.01, 0.0), 0.65);  // the wall, seen twice
    EXPECT_GT(probability(*grid, 2.01, 0.5), 0.65);
    EXPECT_LT(probability(*grid, 1.0, 0.0), 0.35);             // free in front of it
    EXPECT_EQ(grid->LogOdds(grid->CellOf({2.5, 0.0})), 0.0f);  // unknown behind it
  }

  // A missing depth image is an error naming it.
  fs::remove(DepthImagePath(run, "frames/000001"));
  const Result<DepthFusionResult> missing = FuseDepthRun(*depth_run, lidar, trajectory);
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.status().message().find("000001_depth.png"), std::string::npos);
  fs::remove_all(run);
}

}  // namespace
}  // namespace semchain::mapping
