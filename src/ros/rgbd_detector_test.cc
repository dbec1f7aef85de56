#include <gtest/gtest.h>

#include <boost/make_shared.hpp>
#include <opencv2/core.hpp>

#include "detection/testing/square_scene.h"
#include "detection/yolo_detector.h"
#include "ros/node_inputs.h"
#include "ros/ros_image.h"

namespace semchain::ros1 {
namespace {

using detection::testing::SceneSquares;
using detection::testing::SquareClasses;
using detection::testing::SquareImage;
using detection::testing::TestModel;

class RgbdDetectorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Result<std::unique_ptr<detection::YoloDetector>> loaded = detection::YoloDetector::Load(
        TestModel("tiny_squares_raw.onnx"), SquareClasses(), detection::YoloOptions());
    ASSERT_TRUE(loaded.ok()) << loaded.status().message();
    model_ = std::move(*loaded);
  }

  // The colour image of the square scene and a flat depth image 2 m away, stamped 'stamp'.
  static sensor_msgs::ImageConstPtr Color(double stamp, std::uint32_t seq) {
    std_msgs::Header header;
    header.stamp = ::ros::Time(stamp);
    header.seq = seq;
    return boost::make_shared<sensor_msgs::Image>(
        ToColorImageMsg(SquareImage(SceneSquares()), header));
  }
  static sensor_msgs::ImageConstPtr Depth(double stamp) {
    std_msgs::Header header;
    header.stamp = ::ros::Time(stamp);
    const cv::Mat raw(480, 640, CV_16UC1, cv::Scalar(2000));
    return boost::make_shared<sensor_msgs::Image>(ToDepthImageMsg(raw, 0.001, header));
  }

  std::unique_ptr<detection::YoloDetector> model_;
};

// The two topics come on separate connections: whichever image of a moment comes second
// completes the frame, and the frame is the colour image's.
TEST_F(RgbdDetectorTest, PairsColourAndDepthInEitherOrder) {
  RgbdDetector rgbd(model_.get());
  EXPECT_FALSE(rgbd.OnColorImage(Color(10.0, 7)));
  const std::optional<RgbdDetections> colour_first = rgbd.OnDepthImage(Depth(10.0));
  ASSERT_TRUE(colour_first);
  EXPECT_EQ(colour_first->frame, "camera/7");
  EXPECT_DOUBLE_EQ(colour_first->stamp, 10.0);
  EXPECT_EQ(colour_first->detections.size(), SceneSquares().size());
  for (const Detection& detection : colour_first->detections) {
    EXPECT_NEAR(detection.depth_m, 2.0, 1e-6);
  }

  EXPECT_FALSE(rgbd.OnDepthImage(Depth(10.5)));
  const std::optional<RgbdDetections> depth_first = rgbd.OnColorImage(Color(10.5, 8));
  ASSERT_TRUE(depth_first);
  EXPECT_EQ(depth_first->frame, "camera/8");
  EXPECT_EQ(depth_first->detections.size(), SceneSquares().size());
}

TEST_F(RgbdDetectorTest, ImagesOfDifferentMomentsAreNotPaired) {
  RgbdDetector rgbd(model_.get());
  EXPECT_FALSE(rgbd.OnColorImage(Color(10.0, 1)));
  EXPECT_FALSE(rgbd.OnDepthImage(Depth(10.5)));  // half a second later: not this frame's
  EXPECT_FALSE(rgbd.OnColorImage(Color(11.0, 2)));
  // The depth of 10.0 s never came; the next moment still pairs.
  const std::optional<RgbdDetections> next = rgbd.OnDepthImage(Depth(11.0));
  ASSERT_TRUE(next);
  EXPECT_EQ(next->frame, "camera/2");
}

}  // namespace
}  // namespace semchain::ros1
