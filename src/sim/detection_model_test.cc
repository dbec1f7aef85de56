#include "sim/detection_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/prism_silhouette.h"

namespace semchain::sim {
namespace {

// A 20 m × 10 m hall whose detector makes no mistakes unless a test asks for them; the robot's
// camera (320 × 240, 60°, 6 m, 0.5 m high) stands at (2, 5) facing +x.
World PerfectHall() {
  World world;
  world.walls = {{{0, 0}, {20, 0}, {20, 10}, {0, 10}, {0, 0}}};
  world.detection.miss_probability = 0.0;
  world.detection.confusion_probability = 0.0;
  world.detection.false_positives_per_frame = 0.0;
  world.detection.box_noise_px = 0.0;
  world.detection.depth_noise_std = 0.0;
  return world;
}

const Pose2 kPose(2.0, 5.0, 0.0);

Solid Box(const std::string& class_name, double x, double y, double size_x, double size_y,
          double height) {
  Solid solid;
  solid.class_name = class_name;
  solid.footprint.center = {x, y};
  solid.footprint.width = size_x;
  solid.footprint.depth = size_y;
  solid.height = height;
  return solid;
}

Solid Cylinder(const std::string& class_name, double x, double y, double radius, double height) {
  Solid solid = Box(class_name, x, y, 0.0, 0.0, height);
  solid.footprint.shape = Footprint::Shape::kCircle;
  solid.footprint.radius = radius;
  return solid;
}

std::vector<Detection> Detect(const World& world, const Pose2& pose, std::uint64_t seed = 1) {
  const Scene scene(world);
  const MountedCamera camera = MakeMountedCamera(world.robot.camera);
  const RgbdImage image = RenderRgbd(scene, camera, pose);
  Rng rng = MakeRng(seed);
  return DetectObjects(scene, camera, pose, image, rng);
}

std::vector<ObjectVisibility> Visibility(const World& world, const Pose2& pose) {
  const Scene scene(world);
  const MountedCamera camera = MakeMountedCamera(world.robot.camera);
  return MeasureVisibility(scene, camera, pose, RenderRgbd(scene, camera, pose));
}

TEST(DetectionModelTest, CabinetIsReportedAtItsFrontFaceNotItsCentre) {
  World world = PerfectHall();
  world.objects.push_back(Box("cabinet", 4.25, 5.0, 0.5, 0.8, 1.2));  // front face at 2.0 m
  const std::vector<Detection> detections = Detect(world, kPose);
  ASSERT_EQ(detections.size(), 1u);
  const Detection& d = detections[0];
  EXPECT_EQ(d.class_name, "cabinet");
  EXPECT_EQ(d.class_id, 1);             // DefaultClassNames() order
  EXPECT_NEAR(d.depth_m, 2.0, 0.0011);  // the centre is 2.25 m away: a depth camera sees 2.0
  // The front face in pixel-edge coordinates: u = cx + 0.5 ± fx·0.4/2, v from the top edge
  // (0.7 m above the camera) to the floor line.
  const MountedCamera camera = MakeMountedCamera(world.robot.camera);
  const double fx = camera.intrinsics.fx;
  EXPECT_NEAR(d.box[0], 160.0 - fx * 0.2, 1.0);
  EXPECT_NEAR(d.box[2], 160.0 + fx * 0.2, 1.0);
  EXPECT_NEAR(d.box[1], 120.0 - fx * 0.35, 1.0);
  EXPECT_NEAR(d.box[3], 120.0 + fx * 0.25, 1.0);
  EXPECT_GT(d.score, 0.9);
}

TEST(DetectionModelTest, UnoccludedObjectShowsItsWholeSilhouette) {
  World world = PerfectHall();
  world.objects.push_back(Box("chair", 4.5, 4.7, 0.5, 0.5, 0.9));   // seen from the side too
  world.objects.push_back(Cylinder("bucket", 5.0, 5.6, 0.2, 0.4));  // its lid is in view
  for (const ObjectVisibility& view : Visibility(world, kPose)) {
    EXPECT_NEAR(view.VisibleFraction(), 1.0, 0.05);
  }
}

TEST(DetectionModelTest, BucketBehindAColumnIsNotDetected) {
  World world = PerfectHall();
  world.objects.push_back(Cylinder("bucket", 5.0, 5.0, 0.15, 0.4));
  ASSERT_EQ(Detect(world, kPose).size(), 1u);  // in plain view it is seen
  Solid column = Cylinder("", 3.5, 5.0, 0.3, 2.5);
  world.obstacles.push_back(column);
  EXPECT_EQ(Visibility(world, kPose)[0].pixels, 0);
  EXPECT_TRUE(Detect(world, kPose).empty());
}

TEST(DetectionModelTest, ObjectOutsideTheFieldOfViewIsNotDetected) {
  World world = PerfectHall();
  world.objects.push_back(Cylinder("bucket", 0.8, 5.0, 0.15, 0.4));  // behind the robot
  EXPECT_TRUE(Detect(world, kPose).empty());
  EXPECT_EQ(Detect(world, Pose2(2.0, 5.0, 3.14159)).size(), 1u);
  world.objects[0].footprint.center = {3.0, 7.0};  // 63 degrees to the left: outside 60°
  EXPECT_TRUE(Detect(world, kPose).empty());
}

TEST(DetectionModelTest, ObjectBeyondTheDepthRangeIsNotDetected) {
  World world = PerfectHall();
  world.objects.push_back(Box("cabinet", 8.5, 5.0, 0.6, 1.0, 1.2));  // front face at 6.2 m
  EXPECT_GT(Visibility(world, kPose)[0].pixels, 500);  // the colour camera sees it ...
  EXPECT_TRUE(Detect(world, kPose).empty());           // ... the depth camera does not
  world.objects[0].footprint.center.x() = 7.9;         // front face at 5.6 m
  EXPECT_EQ(Detect(world, kPose).size(), 1u);
}

TEST(DetectionModelTest, VisibleFractionDecidesPartlyHiddenObjects) {
  World world = PerfectHall();
  world.objects.push_back(Box("cabinet", 5.1, 5.0, 0.2, 1.0, 1.2));  // front face at 3 m
  world.obstacles.push_back(Cylinder("", 3.5, 5.0, 0.1, 2.5));       // hides about 0.4 m of it
  const ObjectVisibility view = Visibility(world, kPose)[0];
  // The column's shadow at 3 m: ±3·asin(0.1 / 1.5) of the cabinet's 1 m.
  const double hidden = 2.0 * 3.0 * std::tan(std::asin(0.1 / 1.5));
  EXPECT_NEAR(view.VisibleFraction(), 1.0 - hidden, 0.03);
  world.detection.min_visible_fraction = 0.7;
  EXPECT_TRUE(Detect(world, kPose).empty());
  world.detection.min_visible_fraction = 0.5;
  EXPECT_EQ(Detect(world, kPose).size(), 1u);
}

TEST(DetectionModelTest, TinyObjectsAreNotDetected) {
  World world = PerfectHall();
  world.objects.push_back(Cylinder("bucket", 7.0, 5.0, 0.05, 0.4));  // about 6 px wide
  EXPECT_GT(Visibility(world, kPose)[0].pixels, 0);
  EXPECT_TRUE(Detect(world, kPose).empty());
}

TEST(DetectionModelTest, MissesAndConfusions) {
  World world = PerfectHall();
  world.objects.push_back(Box("cabinet", 4.25, 5.0, 0.5, 0.8, 1.2));
  world.detection.miss_probability = 1.0;
  EXPECT_TRUE(Detect(world, kPose).empty());
  world.detection.miss_probability = 0.0;
  world.detection.confusion_probability = 1.0;
  const Scene scene(world);
  const MountedCamera camera = MakeMountedCamera(world.robot.camera);
  const RgbdImage image = RenderRgbd(scene, camera, kPose);
  Rng rng = MakeRng(4);
  std::vector<int> counts(DefaultClassNames().size(), 0);
  for (int frame = 0; frame < 400; ++frame) {
    const std::vector<Detection> detections = DetectObjects(scene, camera, kPose, image, rng);
    ASSERT_EQ(detections.size(), 1u);
    ASSERT_GE(detections[0].class_id, 0);
    ++counts[detections[0].class_id];
    EXPECT_EQ(detections[0].class_name, DefaultClassNames()[detections[0].class_id]);
  }
  EXPECT_EQ(counts[1], 0);  // never the true class; each of the nine others about 44 times
  for (int c : {0, 2, 3, 4, 5, 6, 7, 8, 9}) EXPECT_GT(counts[c], 22) << c;
}

TEST(DetectionModelTest, FalsePositivesLieOnTheBackgroundWithItsDepth) {
  World world = PerfectHall();
  world.walls.push_back({{5, 0}, {5, 10}});  // a wall 3 m ahead fills the view with depth
  world.detection.false_positives_per_frame = 3.0;
  const Scene scene(world);
  const MountedCamera camera = MakeMountedCamera(world.robot.camera);
  const RgbdImage image = RenderRgbd(scene, camera, kPose);
  Rng rng = MakeRng(9);
  int total = 0;
  const int frames = 100;
  for (int frame = 0; frame < frames; ++frame) {
    for (const Detection& d : DetectObjects(scene, camera, kPose, image, rng)) {
      ++total;
      EXPECT_LT(d.score, 0.6);
      EXPECT_GE(d.box[0], 0.0);
      EXPECT_LE(d.box[2], 320.0);
      EXPECT_GE(d.box[1], 0.0);
      EXPECT_LE(d.box[3], 240.0);
      EXPECT_GE(std::min(d.box[2] - d.box[0], d.box[3] - d.box[1]), 12.0);
      const int u = static_cast<int>(0.5 * (d.box[0] + d.box[2]));
      const int v = static_cast<int>(0.5 * (d.box[1] + d.box[3]));
      EXPECT_DOUBLE_EQ(d.depth_m, 0.001 * image.depth.at<std::uint16_t>(v, u));
    }
  }
  EXPECT_NEAR(static_cast<double>(total) / frames, 3.0, 0.6);
}

TEST(DetectionModelTest, SameSeedSameDetections) {
  World world = PerfectHall();
  world.objects.push_back(Box("cabinet", 4.25, 5.0, 0.5, 0.8, 1.2));
  world.detection = DetectionModelSpec();  // the default error model, noise and all
  const std::vector<Detection> a = Detect(world, kPose, 3);
  const std::vector<Detection> b = Detect(world, kPose, 3);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].class_id, b[i].class_id);
    EXPECT_EQ(a[i].depth_m, b[i].depth_m);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(a[i].box[k], b[i].box[k]);
  }
}

TEST(PrismSilhouetteTest, FrontalBoxProjectsToItsAnalyticRectangle) {
  const MountedCamera camera = MakeMountedCamera(CameraSpec());
  const Solid box = Box("cabinet", 4.25, 5.0, 0.5, 0.8, 0.5);  // front at 2 m, back at 2.5 m
  const std::vector<Eigen::Vector2d> outline = ProjectPrism(box, camera, kPose);
  const double fx = camera.intrinsics.fx;
  // The near face, 0.8 m × 0.5 m at 2 m, bounds it: the top is at the camera's height, so both
  // faces' top edges lie on the horizon, and the far face's other edges are inside.
  const double expected = (fx * 0.8 / 2.0) * (fx * 0.5 / 2.0);
  EXPECT_NEAR(AreaInsideImage(outline, 320, 240), expected, 1e-6 * expected);
  // Only the part inside the image counts.
  const Solid wide = Box("cabinet", 4.25, 5.0, 0.5, 8.0, 0.5);
  const double inside = AreaInsideImage(ProjectPrism(wide, camera, kPose), 320, 240);
  EXPECT_NEAR(inside, 320.0 * fx * 0.5 / 2.0, 1e-6 * inside);
}

}  // namespace
}  // namespace semchain::sim
