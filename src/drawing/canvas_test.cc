#include "drawing/canvas.h"

#include <gtest/gtest.h>

namespace semchain::drawing {
namespace {

TEST(TopDownCanvasTest, MapsMetresToPixelsWithYUp) {
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

TEST(TopDownCanvasTest, RefusesHugeAndEmptyImages) {
  Bounds bounds;
  EXPECT_FALSE(TopDownCanvas::Create(bounds, {}).ok());
  bounds.Add({0.0, 0.0});
  bounds.Add({1000.0, 10.0});
  const Result<TopDownCanvas> canvas = TopDownCanvas::Create(bounds, {});
  ASSERT_FALSE(canvas.ok());
  EXPECT_NE(canvas.status().message().find("lower the scale"), std::string::npos);
}

TEST(TopDownCanvasTest, LegendPanelWidensTheImageOnlyWhenItHasEntries) {
  Bounds bounds;
  bounds.Add({0.0, 0.0});
  bounds.Add({2.0, 1.0});
  Result<TopDownCanvas> canvas = TopDownCanvas::Create(bounds, {});
  ASSERT_TRUE(canvas.ok());
  EXPECT_EQ(canvas->Compose().cols, canvas->image().cols);
  canvas->AddLegend("wall", {0, 0, 0}, TopDownCanvas::Swatch::kLine);
  canvas->AddLegend("wall", {0, 0, 0}, TopDownCanvas::Swatch::kLine);  // listed once
  EXPECT_EQ(canvas->Compose().cols, canvas->image().cols + DrawingOptions().legend_width_px);
}

}  // namespace
}  // namespace semchain::drawing
