#include "drawing/plots.h"

#include <gtest/gtest.h>

namespace semchain::drawing {
namespace {

cv::Vec3b At(TopDownCanvas& canvas, const Eigen::Vector2d& p) {
  const cv::Point2d px = canvas.ToPixel(p);
  return canvas.image().at<cv::Vec3b>(static_cast<int>(px.y), static_cast<int>(px.x));
}

TopDownCanvas SquareCanvas() {
  Bounds bounds;
  bounds.Add({0.0, 0.0});
  bounds.Add({6.0, 6.0});
  return *TopDownCanvas::Create(bounds, {});
}

TEST(PlotsTest, DrawsTrajectoriesAndPoints) {
  TopDownCanvas canvas = SquareCanvas();
  const std::vector<Pose2> path = {Pose2(1.5, 2.0, 0.0), Pose2(2.5, 2.0, 0.0),
                                   Pose2(3.0, 2.5, 1.0)};
  DrawTrajectory(path, {0, 200, 0}, "truth", canvas);
  EXPECT_EQ(At(canvas, {2.0, 2.0}), cv::Vec3b(0, 200, 0));
  EXPECT_EQ(At(canvas, {2.0, 4.0}), cv::Vec3b(255, 255, 255));
  DrawPoints({{1.234, 5.0}}, {255, 0, 255}, "scans", canvas);
  EXPECT_EQ(At(canvas, {1.234, 5.0}), cv::Vec3b(255, 0, 255));
  EXPECT_EQ(canvas.Compose().cols, canvas.image().cols + DrawingOptions().legend_width_px);
}

TEST(PlotsTest, GreyImageLandsAtItsOrigin) {
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

}  // namespace
}  // namespace semchain::drawing
