#include "sim/rgbd_renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "core/angles.h"
#include "core/transforms.h"
#include "sim/furnished_room.h"

namespace semchain::sim {
namespace {

// A 20 m × 10 m hall: the camera at x = 2 facing +x sees the wall x = 5 when a wall segment
// is added there.
World Hall() {
  World world;
  world.walls = {{{0, 0}, {20, 0}, {20, 10}, {0, 10}, {0, 0}}};
  world.wall_height = 2.5;
  return world;
}

Solid Box(double x, double y, double width, double depth, double height) {
  return MakeBoxSolid("cabinet", x, y, width, depth, height);
}

// A camera 0.5 m above the floor, 320 × 240, 60° wide, 6 m range (CameraSpec's defaults).
MountedCamera DefaultCamera(double pitch_deg = 0.0) {
  CameraSpec spec;
  spec.pitch_deg = pitch_deg;
  return MakeMountedCamera(spec);
}

int DepthAt(const RgbdImage& image, int u, int v) { return image.depth.at<std::uint16_t>(v, u); }
int IdAt(const RgbdImage& image, int u, int v) { return image.object_ids.at<std::int32_t>(v, u); }

TEST(RgbdRendererTest, MountedCameraFollowsTheSpec) {
  CameraSpec spec;
  spec.forward_offset = 0.1;
  spec.pitch_deg = 10.0;
  const MountedCamera camera = MakeMountedCamera(spec);
  EXPECT_EQ(camera.intrinsics.width, 320);
  EXPECT_EQ(camera.intrinsics.height, 240);
  EXPECT_NEAR(camera.intrinsics.fx, 160.0 / std::tan(DegToRad(30.0)), 1e-9);
  EXPECT_TRUE(camera.robot_from_camera.translation().isApprox(Eigen::Vector3d(0.1, 0.0, 0.5)));
  // The optical axis points forward and 10 degrees down.
  const Eigen::Vector3d axis = camera.robot_from_camera.linear().col(2);
  EXPECT_NEAR(axis.z(), -std::sin(DegToRad(10.0)), 1e-12);
  EXPECT_DOUBLE_EQ(camera.max_range, 6.0);
}

TEST(RgbdRendererTest, FrontalWallAtThreeMetres) {
  World world = Hall();
  world.walls.push_back({{5, 0}, {5, 10}});
  world.wall_height = 1.5;  // low enough that its top edge is in view
  const RgbdImage image = RenderRgbd(Scene(world), DefaultCamera(), Pose2(2.0, 5.0, 0.0));
  ASSERT_EQ(image.depth.type(), CV_16UC1);
  // Depth is along the optical axis: the whole frontal wall reads 3 m, not only the centre.
  EXPECT_NEAR(DepthAt(image, 159, 119), 3000, 1);
  EXPECT_NEAR(DepthAt(image, 0, 100), 3000, 1);
  EXPECT_NEAR(DepthAt(image, 319, 130), 3000, 1);
  EXPECT_EQ(IdAt(image, 159, 119), -1);
  // Rows above the wall's top edge (1 m above the camera) see the ceiling: no depth.
  const double fy = DefaultCamera().intrinsics.fy;
  const int top_row = static_cast<int>(std::floor(119.5 - fy * 1.0 / 3.0));
  EXPECT_EQ(DepthAt(image, 159, top_row - 2), 0);
  EXPECT_NEAR(DepthAt(image, 159, top_row + 2), 3000, 1);
}

TEST(RgbdRendererTest, FloorDepthFollowsTheElevation) {
  const MountedCamera camera = DefaultCamera();
  const RgbdImage image = RenderRgbd(Scene(Hall()), camera, Pose2(2.0, 5.0, 0.0));
  for (int v : {150, 180, 239}) {
    // Pitch 0: the ray through row v descends by (v - cy) / fy per metre ahead, so the floor
    // is met at depth h / tan(elevation).
    const double tan_elevation = (v - camera.intrinsics.cy) / camera.intrinsics.fy;
    EXPECT_NEAR(DepthAt(image, 40, v), 1000.0 * 0.5 / tan_elevation, 1.0) << "row " << v;
  }
  // Row 140 meets the floor 6.8 m ahead, beyond the camera's 6 m: no measurement.
  EXPECT_EQ(DepthAt(image, 40, 140), 0);
}

TEST(RgbdRendererTest, LowBoxInFrontOfTheWall) {
  World world = Hall();
  world.walls.push_back({{5, 0}, {5, 10}});
  world.objects.push_back(Box(3.7, 5.0, 0.4, 1.0, 0.3));  // front face at x = 3.5
  const MountedCamera camera = DefaultCamera();
  const RgbdImage image = RenderRgbd(Scene(world), camera, Pose2(2.0, 5.0, 0.0));
  const double fy = camera.intrinsics.fy, cy = camera.intrinsics.cy;
  // The front face spans heights 0..0.3 m at 1.5 m: rows cy + fy·0.2/1.5 .. cy + fy·0.5/1.5.
  for (int v = static_cast<int>(cy + fy * 0.2 / 1.5) + 1; v < cy + fy * 0.5 / 1.5; ++v) {
    EXPECT_NEAR(DepthAt(image, 159, v), 1500, 1) << "row " << v;
    EXPECT_EQ(IdAt(image, 159, v), 0);
  }
  // Looking down over the front edge the camera sees the lid, 0.2 m below it, until its back
  // edge at 1.9 m.
  const int lid_row = 152;
  EXPECT_NEAR(DepthAt(image, 159, lid_row), 1000.0 * 0.2 / ((lid_row - cy) / fy), 1.0);
  EXPECT_EQ(IdAt(image, 159, lid_row), 0);
  // Above the lid's far edge the wall at 3 m shows over the box.
  for (int v = 100; v < cy + fy * 0.2 / 1.9; ++v) {
    EXPECT_NEAR(DepthAt(image, 159, v), 3000, 1) << "row " << v;
    EXPECT_EQ(IdAt(image, 159, v), -1);
  }
}

TEST(RgbdRendererTest, NearBoxHidesTheFarBox) {
  World world = Hall();
  world.objects.push_back(Box(4.0, 5.0, 0.2, 0.6, 1.0));  // near: front face at 1.9 m
  world.objects.push_back(Box(5.0, 5.0, 0.2, 3.0, 1.0));  // far: wider, same height
  const MountedCamera camera = DefaultCamera();
  const RgbdImage image = RenderRgbd(Scene(world), camera, Pose2(2.0, 5.0, 0.0));
  // Columns whose rays pass within the near box's width (±0.3 m at 1.9 m) never see the far
  // box: below the near box's top the near box is in front, above it both are below the ray.
  const double half_columns = camera.intrinsics.fx * 0.3 / 1.9;
  int near_pixels = 0;
  for (int u = static_cast<int>(159.5 - half_columns) + 1; u < 159.5 + half_columns; ++u) {
    for (int v = 0; v < image.depth.rows; ++v) {
      EXPECT_NE(IdAt(image, u, v), 1) << u << "," << v;
      near_pixels += IdAt(image, u, v) == 0;
    }
  }
  EXPECT_GT(near_pixels, 1000);
  // Beside the near box the far one shows, at its own depth of 2.9 m.
  EXPECT_EQ(IdAt(image, 40, 125), 1);
  EXPECT_NEAR(DepthAt(image, 40, 125), 2900, 1);
}

TEST(RgbdRendererTest, CylinderDepthMatchesItsNearestPoint) {
  World world = Hall();
  Solid bucket = Box(4.0, 5.0, 0.0, 0.0, 0.4);
  bucket.class_name = "bucket";
  bucket.footprint.shape = Footprint::Shape::kCircle;
  bucket.footprint.radius = 0.25;
  world.objects.push_back(bucket);
  const MountedCamera camera = DefaultCamera();
  const RgbdImage image = RenderRgbd(Scene(world), camera, Pose2(2.0, 5.0, 0.0));
  // The central column meets the cylinder at x = 3.75; rows below 0.4 m there see its side.
  const int v = static_cast<int>(camera.intrinsics.cy + camera.intrinsics.fy * 0.3 / 1.75);
  EXPECT_EQ(IdAt(image, 160, v), 0);
  EXPECT_NEAR(DepthAt(image, 160, v), 1750, 2);
}

TEST(RgbdRendererTest, PitchedCameraSeesTheFloorAndWallExactly) {
  World world = Hall();
  world.walls.push_back({{5, 0}, {5, 10}});
  const double pitch = DegToRad(20.0);
  const MountedCamera camera = DefaultCamera(20.0);
  const RgbdImage image = RenderRgbd(Scene(world), camera, Pose2(2.0, 5.0, 0.0));
  const PinholeCamera& k = camera.intrinsics;
  for (const auto& [u, v] : std::vector<std::pair<int, int>>{{10, 230}, {300, 200}, {160, 239}}) {
    // The ray (a, b, 1) descends by sin p + b cos p per unit of depth.
    const double b = (v - k.cy) / k.fy;
    EXPECT_NEAR(DepthAt(image, u, v), 1000.0 * 0.5 / (std::sin(pitch) + b * std::cos(pitch)), 1)
        << u << "," << v;
  }
  for (const auto& [u, v] : std::vector<std::pair<int, int>>{{5, 5}, {160, 40}, {315, 60}}) {
    // ... and advances by cos p - b sin p towards the wall 3 m ahead.
    const double b = (v - k.cy) / k.fy;
    EXPECT_NEAR(DepthAt(image, u, v), 1000.0 * 3.0 / (std::cos(pitch) - b * std::sin(pitch)), 1)
        << u << "," << v;
  }
}

TEST(RgbdRendererTest, DepthBeyondRangeIsZeroButColourStillShows) {
  World world = Hall();
  world.walls.push_back({{9, 0}, {9, 10}});  // 7 m away, beyond the 6 m range
  const RgbdImage image = RenderRgbd(Scene(world), DefaultCamera(), Pose2(2.0, 5.0, 0.0));
  EXPECT_EQ(DepthAt(image, 160, 119), 0);
  const cv::Vec3b wall = image.rgb.at<cv::Vec3b>(119, 160);
  const cv::Vec3b ceiling = image.rgb.at<cv::Vec3b>(0, 160);
  EXPECT_NE(wall, ceiling);
}

TEST(RgbdRendererTest, SameInputsGiveIdenticalBytes) {
  const World world = FurnishedRoomWorld();
  const Scene scene(world);
  RenderOptions options = MakeRenderOptions(world.robot.camera, 42);
  options.depth_noise_std_meters = 0.01;
  const MountedCamera camera = MakeMountedCamera(world.robot.camera);
  const Pose2 pose(2.5, 2.5, 0.3);
  const RgbdImage a = RenderRgbd(scene, camera, pose, options);
  const RgbdImage b = RenderRgbd(scene, camera, pose, options);
  EXPECT_EQ(cv::norm(a.rgb, b.rgb, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.depth, b.depth, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.object_ids, b.object_ids, cv::NORM_INF), 0.0);
  options.noise_seed = 43;  // another frame: other noise, same colours
  const RgbdImage c = RenderRgbd(scene, camera, pose, options);
  EXPECT_GT(cv::norm(a.depth, c.depth, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.rgb, c.rgb, cv::NORM_INF), 0.0);
}

TEST(RgbdRendererTest, DepthNoiseHasTheRequestedSpread) {
  World world = Hall();
  world.walls.push_back({{5, 0}, {5, 10}});
  RenderOptions options;
  options.depth_noise_std_meters = 0.02;
  options.noise_seed = 5;
  const RgbdImage image = RenderRgbd(Scene(world), DefaultCamera(), Pose2(2.0, 5.0, 0.0), options);
  const cv::Mat band = image.depth(cv::Rect(0, 80, 320, 40));  // all on the wall at 3 m
  cv::Scalar mean, stddev;
  cv::meanStdDev(band, mean, stddev);
  EXPECT_NEAR(mean[0], 3000.0, 1.0);
  EXPECT_NEAR(stddev[0], 20.0, 1.0);
}

TEST(RgbdRendererTest, OrbFindsPlentyOfFeaturesInAFurnishedRoom) {
  const World world = FurnishedRoomWorld();
  const Scene scene(world);
  const MountedCamera camera = MakeMountedCamera(world.robot.camera);  // 320 × 240
  cv::Ptr<cv::ORB> orb = cv::ORB::create(500);
  for (const Pose2& pose : {Pose2(2.0, 3.0, 0.0), Pose2(3.0, 1.5, 1.2), Pose2(6.0, 2.0, 2.5)}) {
    const RgbdImage image = RenderRgbd(scene, camera, pose);
    cv::Mat gray;
    cv::cvtColor(image.rgb, gray, cv::COLOR_RGB2GRAY);
    std::vector<cv::KeyPoint> keypoints;
    orb->detect(gray, keypoints);
    EXPECT_GE(keypoints.size(), 200u) << pose;
  }
}

// Keypoints and descriptors of a rendered frame.
struct OrbFeatures {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
};

OrbFeatures Orb(const RgbdImage& image) {
  cv::Mat gray;
  cv::cvtColor(image.rgb, gray, cv::COLOR_RGB2GRAY);
  OrbFeatures features;
  cv::ORB::create(500)->detectAndCompute(gray, cv::noArray(), features.keypoints,
                                         features.descriptors);
  return features;
}

TEST(RgbdRendererTest, TexturesStayPutWhenTheCameraMoves) {
  // Textures live on the surfaces, so ORB matches between two nearby views must agree with
  // the geometry: a keypoint of view A, lifted with A's depth and moved into view B, lands on
  // its match there.
  const World world = FurnishedRoomWorld();
  const Scene scene(world);
  const MountedCamera camera = MakeMountedCamera(world.robot.camera);
  const Pose2 pose_a(2.0, 3.0, 0.0), pose_b(2.3, 3.1, 0.08);
  const RgbdImage a = RenderRgbd(scene, camera, pose_a), b = RenderRgbd(scene, camera, pose_b);
  const OrbFeatures fa = Orb(a), fb = Orb(b);
  std::vector<cv::DMatch> matches;
  cv::BFMatcher(cv::NORM_HAMMING, /*crossCheck=*/true)
      .match(fa.descriptors, fb.descriptors, matches);
  const Eigen::Isometry3d b_from_a = (WorldFromRobot(pose_b) * camera.robot_from_camera).inverse() *
                                     (WorldFromRobot(pose_a) * camera.robot_from_camera);
  int consistent = 0, measured = 0;
  for (const cv::DMatch& match : matches) {
    const cv::Point2f pa = fa.keypoints[match.queryIdx].pt, pb = fb.keypoints[match.trainIdx].pt;
    const int depth_mm =
        DepthAt(a, static_cast<int>(std::lround(pa.x)), static_cast<int>(std::lround(pa.y)));
    if (depth_mm == 0) continue;
    ++measured;
    const Eigen::Vector3d in_b =
        b_from_a * camera.intrinsics.Backproject(pa.x, pa.y, 0.001 * depth_mm);
    const Eigen::Vector2d predicted = camera.intrinsics.Project(in_b);
    consistent += (predicted - Eigen::Vector2d(pb.x, pb.y)).norm() < 3.0;
  }
  EXPECT_GE(consistent, 120) << "of " << measured << " matches with depth";
  EXPECT_GE(consistent, 0.7 * measured);  // the rest: look-alike tiles and bricks
}

}  // namespace
}  // namespace semchain::sim
