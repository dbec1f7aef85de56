#include "detection/box_depth.h"

#include <gtest/gtest.h>

#include <limits>

namespace semchain::detection {
namespace {

TEST(BoxDepthTest, UsesTheCoreOfTheBoxOnly) {
  // A 20 x 20 box at (10, 10); its central half (pixels 15..24) holds the object at 2 m, the
  // rest of the box the wall behind it at 5 m.
  cv::Mat depth(60, 60, CV_32FC1, cv::Scalar(5.0f));
  depth(cv::Rect(15, 15, 10, 10)).setTo(2.0f);
  const double box[4] = {10, 10, 30, 30};
  EXPECT_EQ(BoxDepth(depth, box, BoxDepthOptions()), 2.0);
  BoxDepthOptions whole;
  whole.core_fraction = 1.0;  // 100 of 400 pixels at 2 m: the median is the wall
  EXPECT_EQ(BoxDepth(depth, box, whole), 5.0);
}

TEST(BoxDepthTest, TakesTheMedianOfValidDepths) {
  cv::Mat depth(40, 40, CV_32FC1, cv::Scalar(0.0f));
  // Core of box [0, 8) x [0, 4): columns 2..5, rows 1..2 (8 pixels).
  const double box[4] = {0, 0, 8, 4};
  const float values[8] = {1.0f, 0.0f, 3.0f, 2.0f, 4.0f, std::numeric_limits<float>::quiet_NaN(),
                           7.0f, 0.0f};
  for (int i = 0; i < 8; ++i) depth.at<float>(1 + i / 4, 2 + i % 4) = values[i];
  // Valid: 1, 3, 2, 4, 7 (5 of 8): median 3.
  EXPECT_EQ(BoxDepth(depth, box, BoxDepthOptions()), 3.0);
  BoxDepthOptions strict;
  strict.min_valid_fraction = 0.75;
  EXPECT_EQ(BoxDepth(depth, box, strict), std::nullopt);
}

TEST(BoxDepthTest, UsesTheCentrePixelOfATinyBoxAndRejectsBoxesOutside) {
  cv::Mat depth(10, 10, CV_32FC1, cv::Scalar(1.5f));
  depth.at<float>(4, 6) = 2.5f;
  const double tiny[4] = {6.0, 4.2, 6.4, 5.0};  // no pixel centre in its core
  EXPECT_EQ(BoxDepth(depth, tiny, BoxDepthOptions()), 2.5);
  const double outside[4] = {12, 12, 20, 20};
  EXPECT_EQ(BoxDepth(depth, outside, BoxDepthOptions()), std::nullopt);
}

TEST(BoxDepthTest, ValidatesOptions) {
  std::string error;
  BoxDepthOptions options;
  EXPECT_TRUE(options.Validate(&error));
  options.core_fraction = 0.0;
  EXPECT_FALSE(options.Validate(&error));
  EXPECT_EQ(error, "core_fraction must be in (0, 1]");
}

}  // namespace
}  // namespace semchain::detection
