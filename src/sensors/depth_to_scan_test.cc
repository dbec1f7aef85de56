#include "sensors/depth_to_scan.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/angles.h"
#include "core/transforms.h"

namespace semchain {
namespace {

// An axis-aligned box in the robot frame: [x0, x1] × [y0, y1] × [z0, z1], metres.
struct Box {
  double x0, x1, y0, y1, z0, z1;
};

// Distance along a ray (origin o, direction d) to 'box', +inf when missed (slab method).
double HitBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Box& box) {
  double enter = 0.0;
  double leave = std::numeric_limits<double>::infinity();
  const double lo[3] = {box.x0, box.y0, box.z0};
  const double hi[3] = {box.x1, box.y1, box.z1};
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (o[k] < lo[k] || o[k] > hi[k]) return std::numeric_limits<double>::infinity();
      continue;
    }
    const double a = (lo[k] - o[k]) / d[k];
    const double b = (hi[k] - o[k]) / d[k];
    enter = std::max(enter, std::min(a, b));
    leave = std::min(leave, std::max(a, b));
  }
  return enter <= leave ? enter : std::numeric_limits<double>::infinity();
}

// The depth image (z along the optical axis, metres) of a floor at z = 0 and 'boxes', exactly.
cv::Mat RenderDepth(const MountedCamera& camera, const std::vector<Box>& boxes) {
  const PinholeCamera& k = camera.intrinsics;
  cv::Mat depth(k.height, k.width, CV_32FC1, cv::Scalar(0.0f));
  const Eigen::Vector3d o = camera.robot_from_camera.translation();
  for (int v = 0; v < k.height; ++v) {
    for (int u = 0; u < k.width; ++u) {
      // Per metre of depth, so the distance along the ray is the depth itself.
      const Eigen::Vector3d d = camera.robot_from_camera.rotation() * k.Backproject(u, v, 1.0);
      double z = d.z() < 0.0 ? -o.z() / d.z() : std::numeric_limits<double>::infinity();
      for (const Box& box : boxes) z = std::min(z, HitBox(o, d, box));
      if (z <= camera.max_range) depth.at<float>(v, u) = static_cast<float>(z);
    }
  }
  return depth;
}

MountedCamera Camera(double pitch_deg) {
  MountedCamera camera;
  camera.intrinsics = PinholeCamera::FromFov(160, 120, DegToRad(60.0));
  camera.robot_from_camera = RobotFromOpticalCamera(0.1, 0.0, 0.5, 0.0, DegToRad(pitch_deg));
  camera.max_range = 6.0;
  return camera;
}

// A wall across the robot's path whose face is 'x' metres ahead of the robot centre.
Box WallAt(double x) { return {x, x + 0.1, -5.0, 5.0, 0.0, 2.5}; }

// Every bin sees a flat wall 2 m ahead of the camera: range 2 / cos(θ), for a level and for a
// pitched camera (the pitch must not change horizontal ranges).
TEST(DepthToScanTest, FlatWallGivesTheAnalyticRanges) {
  for (const double pitch_deg : {0.0, 20.0}) {
    const MountedCamera camera = Camera(pitch_deg);
    const DepthToScanConverter converter(camera, DepthToScanOptions{});
    EXPECT_NEAR(converter.robot_from_scan().x, 0.1, 1e-12);
    const LaserScan scan = converter.Convert(RenderDepth(camera, {WallAt(2.1)}), 3.5);
    EXPECT_DOUBLE_EQ(scan.timestamp, 3.5);
    // By default fewer bins than columns: equal-angle bins as wide as the central columns.
    EXPECT_LT(scan.size(), 160u);
    EXPECT_GT(scan.size(), 120u);
    // The bins span the horizontal field of view, ±30° for a level camera.
    if (pitch_deg == 0.0) {
      EXPECT_NEAR(scan.angle_min - 0.5 * scan.angle_increment, DegToRad(-30.0), DegToRad(0.3));
      EXPECT_NEAR(scan.BeamAngle(scan.size() - 1) + 0.5 * scan.angle_increment, DegToRad(30.0),
                  DegToRad(0.3));
    }
    std::size_t returns = 0;
    for (std::size_t i = 0; i < scan.size(); ++i) {
      // A level camera sees the wall in every bin; a pitched one sees the image corners only
      // on the floor or above the band, so its outermost bins may stay empty.
      if (pitch_deg == 0.0 || std::abs(scan.BeamAngle(i)) < DegToRad(25.0)) {
        ASSERT_TRUE(scan.IsReturn(i)) << "bin " << i;
      }
      if (!scan.IsReturn(i)) continue;
      ++returns;
      const double angle = scan.BeamAngle(i);
      // The nearest point of a bin lies within half a bin of its centre angle.
      const double tolerance = 2.0 * std::tan(std::abs(angle) + scan.angle_increment) *
                                   scan.angle_increment / std::cos(angle) +
                               1e-4;
      EXPECT_NEAR(scan.ranges[i], 2.0 / std::cos(angle), tolerance)
          << "pitch " << pitch_deg << " bin " << i;
    }
    EXPECT_GE(returns, scan.size() * 8 / 10) << "pitch " << pitch_deg;
  }
}

// A camera looking at the floor only: every floor pixel is below the band, so no returns.
TEST(DepthToScanTest, FloorPixelsAreExcluded) {
  const MountedCamera camera = Camera(30.0);
  const cv::Mat depth = RenderDepth(camera, {});
  ASSERT_GT(cv::countNonZero(depth), depth.rows * depth.cols / 2);  // the floor is in view
  const LaserScan scan = DepthToScanConverter(camera, DepthToScanOptions{}).Convert(depth, 0.0);
  for (std::size_t i = 0; i < scan.size(); ++i) EXPECT_FALSE(scan.IsReturn(i)) << i;

  // With the band reaching below the floor the same pixels are obstacles: the band decides.
  DepthToScanOptions with_floor;
  with_floor.min_height_meters = -0.1;
  const LaserScan floor = DepthToScanConverter(camera, with_floor).Convert(depth, 0.0);
  // The nearest floor point a bin sees lies at the bottom image edge: 0.5 / tan(30° + vfov/2).
  const double half_vfov = std::atan(59.5 / camera.intrinsics.fy);
  const double nearest = 0.5 / std::tan(DegToRad(30.0) + half_vfov);
  EXPECT_NEAR(floor.ranges[floor.size() / 2], nearest, 0.01);
}

// A 0.13 m box (below a 0.19 m lidar plane) 1.5 m ahead of the camera in front of a wall at
// 3 m: inside the default band it is the nearest obstacle; with the band starting above it
// the bins see the wall behind it.
TEST(DepthToScanTest, LowBoxInsideAndOutsideTheBand) {
  const MountedCamera camera = Camera(0.0);
  const Box low_box{1.6, 1.9, -0.15, 0.15, 0.0, 0.13};
  const cv::Mat depth = RenderDepth(camera, {low_box, WallAt(3.1)});
  const DepthToScanConverter in_band(camera, DepthToScanOptions{});
  DepthToScanOptions above_box;
  above_box.min_height_meters = 0.15;
  const DepthToScanConverter out_of_band(camera, above_box);
  const LaserScan with_box = in_band.Convert(depth, 0.0);
  const LaserScan without_box = out_of_band.Convert(depth, 0.0);
  int box_bins = 0;
  for (std::size_t i = 0; i < with_box.size(); ++i) {
    const double angle = with_box.BeamAngle(i);
    // Bins well inside the box's angular extent (±0.15 m at 1.5 m: ±5.7°).
    if (std::abs(angle) < DegToRad(4.5)) {
      ++box_bins;
      EXPECT_NEAR(with_box.ranges[i], 1.5 / std::cos(angle), 0.01) << i;
      EXPECT_NEAR(without_box.ranges[i], 3.0 / std::cos(angle), 0.02) << i;
    } else if (std::abs(angle) > DegToRad(7.0)) {
      EXPECT_NEAR(with_box.ranges[i], 3.0 / std::cos(angle), 0.02) << i;
    }
  }
  EXPECT_GT(box_bins, 10);
}

// A bin count other than the image width: the bins still span the field of view.
TEST(DepthToScanTest, BinCountIsAnOption) {
  const MountedCamera camera = Camera(0.0);
  DepthToScanOptions options;
  options.beams = 31;
  const LaserScan scan =
      DepthToScanConverter(camera, options).Convert(RenderDepth(camera, {WallAt(2.1)}), 0.0);
  ASSERT_EQ(scan.size(), 31u);
  EXPECT_NEAR(scan.angle_increment * 31, DegToRad(60.0), DegToRad(0.5));
  EXPECT_NEAR(scan.ranges[15], 2.0, 1e-3);
}

TEST(DepthToScanTest, OptionsValidate) {
  std::string error;
  EXPECT_TRUE(DepthToScanOptions{}.Validate(&error));
  DepthToScanOptions bad;
  bad.max_height_meters = 0.0;
  EXPECT_FALSE(bad.Validate(&error));
  EXPECT_NE(error.find("min_height"), std::string::npos);
}

}  // namespace
}  // namespace semchain
