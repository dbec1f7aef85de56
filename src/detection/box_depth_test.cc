#include "detection/box_depth.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace semchain::detection {
namespace {

BoxDepthOptions CoreMedian() {
  BoxDepthOptions options;
  options.method = BoxDepthMethod::kCoreMedian;
  return options;
}

// The simulator's camera: 320 x 240, level, 0.5 m above the floor, looking along the robot's x.
MountedCamera LevelCamera() {
  MountedCamera camera;
  camera.intrinsics = PinholeCamera{320, 240, 277.128129, 277.128129, 159.5, 119.5};
  Eigen::Matrix3d rotation;
  rotation << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  camera.robot_from_camera.linear() = rotation;
  camera.robot_from_camera.translation() = Eigen::Vector3d(0, 0, 0.5);
  return camera;
}

// What LevelCamera() sees facing a wall 'wall' metres ahead across an empty floor: the depth
// of the floor (z = 0) below the horizon where it is nearer than the wall, else the wall.
cv::Mat WallAndFloor(const MountedCamera& camera, float wall) {
  const PinholeCamera& k = camera.intrinsics;
  cv::Mat depth(k.height, k.width, CV_32FC1, cv::Scalar(wall));
  for (int v = 0; v < k.height; ++v) {
    const double below_axis = (v - k.cy) / k.fy;  // the ray's drop per metre of depth
    if (below_axis <= 0.0) continue;
    const double floor = camera.robot_from_camera.translation().z() / below_axis;
    if (floor < wall) depth.row(v).setTo(static_cast<float>(floor));
  }
  return depth;
}

TEST(BoxDepthTest, FindsAnOpenObjectInFrontOfTheWallItsBoxMostlyHolds) {
  // A chair 2 m ahead, seen as its back (rows 90-119) and two legs down to the floor, in a box
  // whose other pixels are the wall 4 m ahead and the floor in between: the box's core is wall
  // and floor, so its median is far behind the chair.
  const MountedCamera camera = LevelCamera();
  cv::Mat depth = WallAndFloor(camera, 4.0f);
  const int floor_row_at_2m = int(std::ceil(119.5 + 0.5 * 277.128129 / 2.0));  // 189
  depth(cv::Range(90, 120), cv::Range(130, 190)).setTo(2.0f);
  for (int leg : {140, 176})
    depth(cv::Range(120, floor_row_at_2m), cv::Range(leg, leg + 4)).setTo(2.0f);
  const double box[4] = {129.5, 89.5, 189.5, floor_row_at_2m - 0.5};
  EXPECT_EQ(BoxDepth(depth, box, &camera, BoxDepthOptions()), 2.0);
  EXPECT_GT(*BoxDepth(depth, box, &camera, CoreMedian()), 3.0);
}

TEST(BoxDepthTest, IgnoresASmallNearerThingAndTakesASolidObjectWhole) {
  // A cabinet 3 m ahead fills its box; a thin pole 1 m ahead covers 4 of the 40 columns the
  // trimmed box keeps.
  const MountedCamera camera = LevelCamera();
  cv::Mat depth = WallAndFloor(camera, 5.0f);
  depth(cv::Range(40, 160), cv::Range(100, 150)).setTo(3.0f);
  depth(cv::Range(0, 240), cv::Range(120, 124)).setTo(1.0f);
  const double box[4] = {99.5, 39.5, 149.5, 159.5};
  EXPECT_EQ(BoxDepth(depth, box, &camera, BoxDepthOptions()), 3.0);
  // Had the pole filled a quarter of the box, it would be the nearest surface.
  depth(cv::Range(0, 240), cv::Range(115, 126)).setTo(1.0f);
  EXPECT_EQ(BoxDepth(depth, box, &camera, BoxDepthOptions()), 1.0);
}

TEST(BoxDepthTest, UsesTheCoreOfTheBoxOnly) {
  // A 20 x 20 box at (10, 10); its central half (pixels 15..24) holds the object at 2 m, the
  // rest of the box the wall behind it at 5 m.
  cv::Mat depth(60, 60, CV_32FC1, cv::Scalar(5.0f));
  depth(cv::Rect(15, 15, 10, 10)).setTo(2.0f);
  const double box[4] = {10, 10, 30, 30};
  EXPECT_EQ(BoxDepth(depth, box, nullptr, CoreMedian()), 2.0);
  BoxDepthOptions whole = CoreMedian();
  whole.core_fraction = 1.0;  // 100 of 400 pixels at 2 m: the median is the wall
  EXPECT_EQ(BoxDepth(depth, box, nullptr, whole), 5.0);
}

TEST(BoxDepthTest, TakesTheMedianOfValidDepths) {
  cv::Mat depth(40, 40, CV_32FC1, cv::Scalar(0.0f));
  // Core of box [0, 8) x [0, 4): columns 2..5, rows 1..2 (8 pixels).
  const double box[4] = {0, 0, 8, 4};
  const float values[8] = {1.0f, 0.0f, 3.0f, 2.0f, 4.0f, std::numeric_limits<float>::quiet_NaN(),
                           7.0f, 0.0f};
  for (int i = 0; i < 8; ++i) depth.at<float>(1 + i / 4, 2 + i % 4) = values[i];
  // Valid: 1, 3, 2, 4, 7 (5 of 8): median 3.
  EXPECT_EQ(BoxDepth(depth, box, nullptr, CoreMedian()), 3.0);
  BoxDepthOptions strict = CoreMedian();
  strict.min_valid_fraction = 0.75;
  EXPECT_EQ(BoxDepth(depth, box, nullptr, strict), std::nullopt);
}

TEST(BoxDepthTest, UsesTheCentrePixelOfATinyBoxAndRejectsBoxesOutside) {
  cv::Mat depth(10, 10, CV_32FC1, cv::Scalar(1.5f));
  depth.at<float>(4, 6) = 2.5f;
  const double tiny[4] = {6.0, 4.2, 6.4, 5.0};  // no pixel centre in its core
  for (const BoxDepthOptions& options : {CoreMedian(), BoxDepthOptions()}) {
    EXPECT_EQ(BoxDepth(depth, tiny, nullptr, options), 2.5);
    const double outside[4] = {12, 12, 20, 20};
    EXPECT_EQ(BoxDepth(depth, outside, nullptr, options), std::nullopt);
  }
}

TEST(BoxDepthTest, ValidatesOptions) {
  std::string error;
  BoxDepthOptions options;
  EXPECT_TRUE(options.Validate(&error));
  options.core_fraction = 0.0;
  EXPECT_FALSE(options.Validate(&error));
  EXPECT_EQ(error, "core_fraction must be in (0, 1]");
  options = BoxDepthOptions();
  options.trim_fraction = 0.5;
  EXPECT_FALSE(options.Validate(&error));
  EXPECT_EQ(error, "trim_fraction must be in [0, 0.5)");
  options = BoxDepthOptions();
  options.surface_gap = 0.0;
  EXPECT_FALSE(options.Validate(&error));
  EXPECT_EQ(error, "surface_gap must be > 0");
}

}  // namespace
}  // namespace semchain::detection
