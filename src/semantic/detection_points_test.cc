#include "semantic/detection_points.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/transforms.h"
#include "semantic/grid_geometry.h"

namespace semchain::semantic {
namespace {

// A level camera 0.5 m up and 0.1 m ahead of the robot centre, looking forward.
MountedCamera LevelCamera() {
  MountedCamera camera;
  camera.intrinsics = PinholeCamera::FromFov(160, 120, M_PI / 2);
  camera.robot_from_camera = RobotFromOpticalCamera(0.1, 0.0, 0.5, 0.0, 0.0);
  return camera;
}

Detection Box(double x1, double y1, double x2, double y2, double depth) {
  return {"cabinet", 1, 0.9, {x1, y1, x2, y2}, depth};
}

TEST(DetectionPointsTest, KnownExtrinsicsPlacePointsOnTheMap) {
  // A wall 2 m in front of the camera fills the image; the robot stands at (1, 2) facing +y.
  const MountedCamera camera = LevelCamera();
  const cv::Mat depth(120, 160, CV_32FC1, cv::Scalar(2.0));
  const Pose2 robot(1.0, 2.0, M_PI / 2);
  DetectionPointOptions options;
  options.box_trim_fraction = 0.0;
  options.min_trim_px = 0.0;
  const std::vector<Eigen::Vector3d> points =
      DetectionWorldPoints(Box(60, 20, 100, 50, 2.0), depth, camera, robot, 0.5, options);
  ASSERT_EQ(points.size(), 40u * 30u);
  const double fx = camera.intrinsics.fx;
  const double cx = camera.intrinsics.cx;
  const double cy = camera.intrinsics.cy;
  for (const Eigen::Vector3d& p : points) {
    // Eq. 2: 2.1 m ahead of the robot; eq. 3–4: ahead is +y in the world.
    EXPECT_NEAR(p.y(), 2.0 + 2.1, 1e-9);
    EXPECT_GE(p.z(), 0.5 - 2.0 * (50 - 0.5 - cy) / fx - 1e-9);
  }
  // Pixel (60, 20): right of the optical axis is the robot's −y, which is world +x here.
  const Eigen::Vector3d& first = points.front();
  EXPECT_NEAR(first.x(), 1.0 + 2.0 * (60 - cx) / fx, 1e-9);
  EXPECT_NEAR(first.z(), 0.5 - 2.0 * (20 - cy) / fx, 1e-9);
  // Eq. 5: the cell of a point, as core/transforms computes it.
  const GridGeometry geometry{100, 100, 0.05, Eigen::Vector2d(-1.0, -1.0)};
  EXPECT_EQ(geometry.CellOf(first.head<2>()),
            WorldToGrid(first.head<2>(), 0.05, Eigen::Vector2d(-1.0, -1.0)));
}

TEST(DetectionPointsTest, DepthGateTrimAndFloorKeepOnlyTheObject) {
  const MountedCamera camera = LevelCamera();
  cv::Mat depth(120, 160, CV_32FC1, cv::Scalar(5.0));  // background wall far behind
  depth(cv::Rect(70, 30, 20, 40)).setTo(2.0);          // the object
  DetectionPointOptions options;
  options.box_trim_fraction = 0.0;
  options.min_trim_px = 0.0;
  const Pose2 robot;
  // A box larger than the object: the background is outside the depth gate.
  const auto points =
      DetectionWorldPoints(Box(60, 20, 100, 80, 2.0), depth, camera, robot, 0.6, options);
  EXPECT_EQ(points.size(), 20u * 40u);
  // Trimming 2 px on each side of an exact box drops its edge columns and rows.
  options.min_trim_px = 2.0;
  EXPECT_EQ(
      DetectionWorldPoints(Box(70, 30, 90, 70, 2.0), depth, camera, robot, 0.6, options).size(),
      16u * 36u);
  // Low scores and boxes without depth give nothing.
  Detection weak = Box(70, 30, 90, 70, 2.0);
  weak.score = 0.1;
  EXPECT_TRUE(DetectionWorldPoints(weak, depth, camera, robot, 0.6, options).empty());
  // Floor pixels (below min_height) are dropped: a camera looking down at the floor.
  MountedCamera down = camera;
  down.robot_from_camera = RobotFromOpticalCamera(0.0, 0.0, 0.5, 0.0, M_PI / 2);
  const cv::Mat floor(120, 160, CV_32FC1, cv::Scalar(0.5));
  EXPECT_TRUE(
      DetectionWorldPoints(Box(0, 0, 160, 120, 0.5), floor, down, robot, 0.6, options).empty());
}

TEST(DetectionPointsTest, FreeSpaceEndsBeforeTheNearestSurface) {
  const MountedCamera camera = LevelCamera();
  const cv::Mat depth(120, 160, CV_32FC1, cv::Scalar(3.0));
  FreeSpaceOptions options;
  options.column_stride = 1;
  options.surface_margin = 0.2;
  const std::vector<FreeRay> rays = FreeSpaceRays(depth, camera, Pose2(), options);
  ASSERT_EQ(rays.size(), 160u);
  const FreeRay& centre = rays[80];
  EXPECT_NEAR(centre.from.x(), 0.1, 1e-9);
  // Column 80 is half a pixel right of the axis: its surface is at x = 3.1 m (plus camera).
  EXPECT_NEAR(centre.surface.x(), 0.1 + 3.0, 1e-9);
  EXPECT_NEAR((centre.surface - centre.to).norm(), 0.2, 1e-9);
}

}  // namespace
}  // namespace semchain::semantic
