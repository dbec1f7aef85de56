#include "ros/ros_image.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <opencv2/imgproc.hpp>

namespace semchain::ros1 {
namespace {

using ::testing::HasSubstr;

bool Same(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

cv::Mat Colors() {
  cv::Mat rgb(3, 5, CV_8UC3);
  cv::randu(rgb, 0, 256);
  return rgb;
}

TEST(RosImageTest, ColourImagesRoundTripInEveryEncodingWeRead) {
  const cv::Mat rgb = Colors();
  const sensor_msgs::Image msg = ToColorImageMsg(rgb, {});
  EXPECT_EQ(msg.encoding, "rgb8");
  EXPECT_EQ(msg.step, 15u);
  Result<cv::Mat> back = ColorFromImageMsg(msg);
  ASSERT_TRUE(back.ok());
  EXPECT_TRUE(Same(*back, rgb));

  // A bgra8 image whose rows are padded to 24 bytes.
  cv::Mat bgra;
  cv::cvtColor(rgb, bgra, cv::COLOR_RGB2BGRA);
  sensor_msgs::Image padded;
  padded.width = 5;
  padded.height = 3;
  padded.encoding = "bgra8";
  padded.step = 24;
  padded.data.assign(72, 0);
  for (int row = 0; row < 3; ++row) {
    std::memcpy(&padded.data[static_cast<std::size_t>(row) * 24], bgra.ptr(row), 20);
  }
  back = ColorFromImageMsg(padded);
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_TRUE(Same(*back, rgb));

  padded.encoding = "yuv422";
  EXPECT_THAT(ColorFromImageMsg(padded).status().message(), HasSubstr("'yuv422' is not one of"));
  padded.encoding = "bgra8";
  padded.data.resize(50);
  EXPECT_THAT(ColorFromImageMsg(padded).status().message(), HasSubstr("do not fill it"));
}

TEST(RosImageTest, MillimetreDepthTravelsAs16UC1) {
  const cv::Mat raw = (cv::Mat_<std::uint16_t>(2, 3) << 1000, 0, 6553, 65535, 1, 2);
  const sensor_msgs::Image msg = ToDepthImageMsg(raw, 0.001, {});
  EXPECT_EQ(msg.encoding, "16UC1");
  Result<cv::Mat> back = DepthFromImageMsg(msg, 0.001);
  ASSERT_TRUE(back.ok());
  EXPECT_TRUE(Same(*back, raw));
  // The same readings for a run whose unit is 0.1 mm; 65.535 m does not fit and reads 0.
  back = DepthFromImageMsg(msg, 0.0001);
  ASSERT_TRUE(back.ok());
  const cv::Mat expected = (cv::Mat_<std::uint16_t>(2, 3) << 10000, 0, 65530, 0, 10, 20);
  EXPECT_TRUE(Same(*back, expected));
}

TEST(RosImageTest, OtherDepthUnitsTravelAs32FC1Metres) {
  cv::Mat raw(2, 3, CV_16UC1);
  cv::randu(raw, 0, 65535);
  const sensor_msgs::Image msg = ToDepthImageMsg(raw, 0.0001, {});
  EXPECT_EQ(msg.encoding, "32FC1");
  Result<cv::Mat> back = DepthFromImageMsg(msg, 0.0001);
  ASSERT_TRUE(back.ok());
  EXPECT_TRUE(Same(*back, raw));

  sensor_msgs::Image metres = msg;
  float* values = reinterpret_cast<float*>(metres.data.data());
  values[0] = std::numeric_limits<float>::quiet_NaN();
  values[1] = -1.0f;
  values[2] = 1.2345f;
  back = DepthFromImageMsg(metres, 0.001);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->at<std::uint16_t>(0, 0), 0);
  EXPECT_EQ(back->at<std::uint16_t>(0, 1), 0);
  EXPECT_EQ(back->at<std::uint16_t>(0, 2), 1235);
}

TEST(RosImageTest, BigEndianDepthIsSwapped) {
  sensor_msgs::Image msg;
  msg.width = 1;
  msg.height = 1;
  msg.encoding = "16UC1";
  msg.is_bigendian = 1;
  msg.step = 2;
  msg.data = {0x01, 0x02};
  const Result<cv::Mat> depth = DepthFromImageMsg(msg, 0.001);
  ASSERT_TRUE(depth.ok());
  EXPECT_EQ(depth->at<std::uint16_t>(0, 0), 0x0102);
}

TEST(RosImageTest, CameraInfoCarriesTheIntrinsics) {
  PinholeCamera camera;
  camera.width = 320;
  camera.height = 240;
  camera.fx = 277.1;
  camera.fy = 277.2;
  camera.cx = 159.5;
  camera.cy = 119.25;
  const sensor_msgs::CameraInfo msg = ToCameraInfoMsg(camera, {});
  bool distortion = true;
  const Result<PinholeCamera> back = FromCameraInfoMsg(msg, &distortion);
  ASSERT_TRUE(back.ok());
  EXPECT_FALSE(distortion);
  EXPECT_EQ(back->fx, 277.1);
  EXPECT_EQ(back->fy, 277.2);
  EXPECT_EQ(back->cx, 159.5);
  EXPECT_EQ(back->cy, 119.25);
  EXPECT_EQ(back->width, 320);
  sensor_msgs::CameraInfo empty;
  EXPECT_THAT(FromCameraInfoMsg(empty, &distortion).status().message(),
              HasSubstr("camera_info has no calibration"));
}

}  // namespace
}  // namespace semchain::ros1
