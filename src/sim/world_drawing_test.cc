#include "sim/world_drawing.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "core/atomic_file.h"
#include "sim/furnished_room.h"

namespace semchain::sim {
namespace {

cv::Vec3b Bgr(const Color& c) { return cv::Vec3b(c[2], c[1], c[0]); }

cv::Vec3b At(TopDownCanvas& canvas, const Eigen::Vector2d& p) {
  const cv::Point2d px = canvas.ToPixel(p);
  return canvas.image().at<cv::Vec3b>(static_cast<int>(px.y), static_cast<int>(px.x));
}

TEST(WorldDrawingTest, CanvasMapsMetresToPixelsWithYUp) {
  Bounds bounds;
  bounds.Add({-1.0, 2.0});
  bounds.Add({3.0, 4.0});
  DrawingOptions options;
  options.pixels_per_meter = 10.0;
  options.margin_px = 5;
  const Result<TopDownCanvas> canvas = TopDownCanvas::Create(bounds, options);
  ASSERT_TRUE(canvas.ok());
  EXPECT_EQ(canvas->Compose().rows, 2 * 10 + 2 * 5 + 1);
  const cv::Point2d top_left = canvas->ToPixel({-1.0, 4.0});
  EXPECT_DOUBLE_EQ(top_left.x, 5.0);
  EXPECT_DOUBLE_EQ(top_left.y, 5.0);
  const cv::Point2d bottom_right = canvas->ToPixel({3.0, 2.0});
  EXPECT_DOUBLE_EQ(bottom_right.x, 45.0);
  EXPECT_DOUBLE_EQ(bottom_right.y, 25.0);
}

TEST(WorldDrawingTest, RefusesHugeAndEmptyImages) {
  Bounds bounds;
  EXPECT_FALSE(TopDownCanvas::Create(bounds, {}).ok());
  bounds.Add({0.0, 0.0});
  bounds.Add({1000.0, 10.0});
  const Result<TopDownCanvas> canvas = TopDownCanvas::Create(bounds, {});
  ASSERT_FALSE(canvas.ok());
  EXPECT_NE(canvas.status().message().find("lower the scale"), std::string::npos);
}

TEST(WorldDrawingTest, DrawsWallsObjectsObstaclesAndTrajectories) {
  const World world = FurnishedRoomWorld();
  Result<TopDownCanvas> canvas = TopDownCanvas::Create(WorldBounds(world), {});
  ASSERT_TRUE(canvas.ok());
  DrawWorld(world, *canvas);
  EXPECT_EQ(At(*canvas, {4.0, 0.0}), cv::Vec3b(0, 0, 0));        // the wall y = 0
  EXPECT_EQ(At(*canvas, {7.7, 3.5}), Bgr(ClassColor(1)));        // the cabinet's centre
  EXPECT_EQ(At(*canvas, {4.0, 2.2}), Bgr({150, 150, 150}));      // the column
  EXPECT_EQ(At(*canvas, {2.0, 4.0}), cv::Vec3b(255, 255, 255));  // free floor
  const std::vector<Pose2> path = {Pose2(1.5, 2.0, 0.0), Pose2(2.5, 2.0, 0.0),
                                   Pose2(3.0, 2.5, 1.0)};
  DrawTrajectory(path, {0, 200, 0}, "truth", *canvas);
  EXPECT_EQ(At(*canvas, {2.0, 2.0}), cv::Vec3b(0, 200, 0));
  DrawPoints({{1.234, 5.0}}, {255, 0, 255}, "scans", *canvas);
  EXPECT_EQ(At(*canvas, {1.234, 5.0}), cv::Vec3b(255, 0, 255));
  // The legend panel widens the image.
  EXPECT_EQ(canvas->Compose().cols, canvas->image().cols + DrawingOptions().legend_width_px);
}

TEST(WorldDrawingTest, GreyImageLandsAtItsOrigin) {
  Bounds bounds;
  bounds.Add({0.0, 0.0});
  bounds.Add({2.0, 2.0});
  Result<TopDownCanvas> canvas = TopDownCanvas::Create(bounds, {});
  ASSERT_TRUE(canvas.ok());
  cv::Mat map(10, 10, CV_8UC1, cv::Scalar(254));  // 1 m × 1 m at 0.1 m per cell
  map.at<std::uint8_t>(0, 0) = 0;                 // top-left cell: x 0.5..0.6, y 1.4..1.5
  DrawGreyImage(map, {0.5, 0.5}, 0.1, *canvas);
  EXPECT_EQ(At(*canvas, {0.55, 1.45}), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(At(*canvas, {0.65, 1.45}), cv::Vec3b(254, 254, 254));
  EXPECT_EQ(At(*canvas, {0.45, 1.45}), cv::Vec3b(255, 255, 255));  // outside the map
}

TEST(WorldDrawingTest, WritesAReadablePng) {
  const World world = FurnishedRoomWorld();
  Result<TopDownCanvas> canvas = TopDownCanvas::Create(WorldBounds(world), {});
  ASSERT_TRUE(canvas.ok());
  DrawWorld(world, *canvas);
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "semchain_world_drawing_test.png";
  ASSERT_TRUE(WritePng(canvas->Compose(), path).ok());
  const cv::Mat read = cv::imread(path.string(), cv::IMREAD_COLOR);
  std::filesystem::remove(path);
  ASSERT_FALSE(read.empty());
  EXPECT_EQ(cv::norm(read, canvas->Compose(), cv::NORM_INF), 0.0);
}

}  // namespace
}  // namespace semchain::sim
