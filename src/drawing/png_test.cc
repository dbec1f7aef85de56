#include "drawing/png.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "drawing/canvas.h"
#include "drawing/plots.h"

namespace semchain::drawing {
namespace {

TEST(PngTest, WritesAReadablePng) {
  Bounds bounds;
  bounds.Add({0.0, 0.0});
  bounds.Add({4.0, 3.0});
  Result<TopDownCanvas> canvas = TopDownCanvas::Create(bounds, {});
  ASSERT_TRUE(canvas.ok());
  DrawTrajectory({Pose2(0.5, 0.5, 0.0), Pose2(3.5, 2.5, 0.5)}, {0, 90, 255}, "path", *canvas);
  const cv::Mat composed = canvas->Compose();
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "semchain_png_test.png";
  ASSERT_TRUE(WritePng(composed, path).ok());
  const cv::Mat read = cv::imread(path.string(), cv::IMREAD_COLOR);
  std::filesystem::remove(path);
  ASSERT_FALSE(read.empty());
  EXPECT_EQ(cv::norm(read, composed, cv::NORM_INF), 0.0);
}

}  // namespace
}  // namespace semchain::drawing
