// `bag import` of cameras as robots record them: image_transport's compressed colour and
// compressedDepth depth, topics found beside each other, an uncalibrated camera_info and a
// colour camera without depth. The bags are written here message by message, the compressed
// images encoded as compressed_image_transport and compressed_depth_image_transport encode them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_msgs/TFMessage.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "io/camera_io.h"
#include "ros/bag_import.h"
#include "ros/bag_writer.h"
#include "ros/ros_compressed_image.h"
#include "ros/ros_geometry.h"
#include "ros/ros_image.h"

namespace semchain::ros1 {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr int kWidth = 8;
constexpr int kHeight = 6;

ros::Time At(double seconds) { return ros::Time(seconds); }

tf2_msgs::TFMessage Tf(double seconds, const std::string& parent, const std::string& child,
                       const Eigen::Isometry3d& pose) {
  geometry_msgs::TransformStamped transform;
  transform.header.stamp = At(seconds);
  transform.header.frame_id = parent;
  transform.child_frame_id = child;
  transform.transform = ToTransformMsg(pose);
  tf2_msgs::TFMessage msg;
  msg.transforms.push_back(transform);
  return msg;
}

// A camera looking ahead from 0.3 m up (optical frame: z forward, x right, y down).
Eigen::Isometry3d CameraMount() {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  pose.translation() = Eigen::Vector3d(0.1, 0.0, 0.3);
  return pose;
}

sensor_msgs::CameraInfo Calibrated(double seconds, const std::string& frame) {
  PinholeCamera camera;
  camera.width = kWidth;
  camera.height = kHeight;
  camera.fx = camera.fy = 5.0;
  camera.cx = 3.5;
  camera.cy = 2.5;
  std_msgs::Header header;
  header.stamp = At(seconds);
  header.frame_id = frame;
  return ToCameraInfoMsg(camera, header);
}

sensor_msgs::CompressedImage Compressed(double seconds, const std::string& format,
                                        std::vector<std::uint8_t> data) {
  sensor_msgs::CompressedImage msg;
  msg.header.stamp = At(seconds);
  msg.header.frame_id = "camera_color_optical_frame";
  msg.format = format;
  msg.data = std::move(data);
  return msg;
}

std::vector<std::uint8_t> Encode(const char* extension, const cv::Mat& image) {
  std::vector<std::uint8_t> bytes;
  EXPECT_TRUE(cv::imencode(extension, image, bytes));
  return bytes;
}

// compressed_image_transport: the RGB image converted to bgr8, then encoded.
sensor_msgs::CompressedImage CompressedColor(double seconds, const cv::Mat& rgb,
                                             const char* codec) {
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  const std::string format = std::string("rgb8; ") + codec + " compressed bgr8";
  return Compressed(seconds, format, Encode(std::string(".").append(codec).c_str(), bgr));
}

// compressed_depth_image_transport: ConfigHeader {int32 format, float depthParam[2]}, then the
// PNG of 'quantized'.
std::vector<std::uint8_t> DepthPayload(float a, float b, const cv::Mat& quantized) {
  std::vector<std::uint8_t> data(12, 0);
  const std::int32_t inverse_depth = 0;
  std::memcpy(data.data(), &inverse_depth, 4);
  std::memcpy(data.data() + 4, &a, 4);
  std::memcpy(data.data() + 8, &b, 4);
  const std::vector<std::uint8_t> png = Encode(".png", quantized);
  data.insert(data.end(), png.begin(), png.end());
  return data;
}

// Depths in metres across the image: near, far, past depth_max (no reading) and NaN.
cv::Mat MetricDepths() {
  cv::Mat metres(kHeight, kWidth, CV_32FC1);
  for (int row = 0; row < kHeight; ++row) {
    for (int col = 0; col < kWidth; ++col) {
      metres.at<float>(row, col) = 0.4f + 0.17f * static_cast<float>(row * kWidth + col);
    }
  }
  metres.at<float>(0, 1) = 12.0f;  // beyond depth_max
  metres.at<float>(0, 2) = std::numeric_limits<float>::quiet_NaN();
  return metres;
}

// The encoder's inverse-depth quantization (depth_quantization 100, depth_max 10 m).
struct InverseDepth {
  float a = 100.0f * (100.0f + 1.0f);
  float b = 1.0f - a / 10.0f;
  cv::Mat Quantize(const cv::Mat& metres) const {
    cv::Mat q(metres.size(), CV_16UC1);
    for (int row = 0; row < metres.rows; ++row) {
      for (int col = 0; col < metres.cols; ++col) {
        const float d = metres.at<float>(row, col);
        q.at<std::uint16_t>(row, col) = d < 10.0f ? static_cast<std::uint16_t>(a / d + b) : 0;
      }
    }
    return q;
  }
};

class CompressedImportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("semchain_compressed_import_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    options_.show_progress = false;
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Writes dir_/in.bag: odometry from 1 s to 3 s, a scan at 1.5 s, the laser's and (with
  // 'camera_frame') the camera's mountings, then 'fill'.
  void WriteBag(const std::string& camera_frame, const std::function<void(BagWriter&)>& fill) {
    Result<std::unique_ptr<BagWriter>> bag =
        BagWriter::Create(dir_ / "in.bag", BagCompression::kNone);
    ASSERT_TRUE(bag.ok());
    BagWriter& writer = **bag;
    Eigen::Isometry3d laser = Eigen::Isometry3d::Identity();
    ASSERT_TRUE(
        writer.Write("/tf_static", At(1.0), Tf(1.0, "base_link", "laser", laser), true).ok());
    if (!camera_frame.empty()) {
      ASSERT_TRUE(
          writer
              .Write("/tf_static", At(1.0), Tf(1.0, "base_link", camera_frame, CameraMount()), true)
              .ok());
    }
    for (const double t : {1.0, 2.0, 3.0}) {
      ASSERT_TRUE(
          writer.Write("/tf", At(t), Tf(t, "odom", "base_link", Eigen::Isometry3d::Identity()))
              .ok());
    }
    sensor_msgs::LaserScan scan;
    scan.header.stamp = At(1.5);
    scan.header.frame_id = "laser";
    scan.angle_min = -1.0f;
    scan.angle_increment = 1.0f;
    scan.angle_max = 1.0f;
    scan.range_max = 8.0f;
    scan.ranges = {1.0f, 2.0f, 3.0f};
    ASSERT_TRUE(writer.Write("/scan", At(1.5), scan).ok());
    fill(writer);
    ASSERT_TRUE(writer.Finish().ok());
  }

  Result<BagImportSummary> Import() {
    return ImportBagToRun(dir_ / "in.bag", dir_ / "run", options_);
  }

  cv::Mat ReadPng(const std::string& name) {
    return cv::imread((dir_ / "run/frames" / name).string(), cv::IMREAD_UNCHANGED);
  }

  fs::path dir_;
  BagImportOptions options_;
};

cv::Mat Gradient() {
  cv::Mat rgb(kHeight, kWidth, CV_8UC3);
  for (int row = 0; row < kHeight; ++row) {
    for (int col = 0; col < kWidth; ++col) {
      rgb.at<cv::Vec3b>(row, col) =
          cv::Vec3b(static_cast<std::uint8_t>(30 * col), static_cast<std::uint8_t>(40 * row), 200);
    }
  }
  return rgb;
}

// The default camera namespace recorded through image_transport: colour on
// /camera/color/image_raw/compressed (png, then jpeg), depth on
// /camera/depth/image_raw/compressedDepth (16UC1 millimetres, then 32FC1 inverse depth).
TEST_F(CompressedImportTest, DecodesCompressedColourAndCompressedDepth) {
  const std::string camera_frame = "camera_color_optical_frame";
  cv::Mat millimetres(kHeight, kWidth, CV_16UC1);
  for (int i = 0; i < kWidth * kHeight; ++i) {
    millimetres.at<std::uint16_t>(i / kWidth, i % kWidth) =
        static_cast<std::uint16_t>(400 + 97 * i);
  }
  millimetres.at<std::uint16_t>(0, 0) = 0;  // no reading
  const InverseDepth inverse;
  const cv::Mat metres = MetricDepths();
  const cv::Mat quantized = inverse.Quantize(metres);
  const cv::Mat orange(kHeight, kWidth, CV_8UC3, cv::Scalar(200, 100, 50));  // RGB
  WriteBag(camera_frame, [&](BagWriter& bag) {
    ASSERT_TRUE(
        bag.Write("/camera/color/camera_info", At(1.1), Calibrated(1.1, camera_frame)).ok());
    const std::string color = "/camera/color/image_raw/compressed";
    const std::string depth = "/camera/depth/image_raw/compressedDepth";
    ASSERT_TRUE(bag.Write(color, At(1.2), CompressedColor(1.2, Gradient(), "png")).ok());
    ASSERT_TRUE(bag.Write(depth, At(1.2),
                          Compressed(1.2, "16UC1; compressedDepth png",
                                     DepthPayload(0.0f, 0.0f, millimetres)))
                    .ok());
    ASSERT_TRUE(bag.Write(color, At(1.6), CompressedColor(1.6, orange, "jpeg")).ok());
    // The older format string, without the codec.
    ASSERT_TRUE(bag.Write(depth, At(1.6),
                          Compressed(1.6, "32FC1; compressedDepth",
                                     DepthPayload(inverse.a, inverse.b, quantized)))
                    .ok());
  });
  const Result<BagImportSummary> summary = Import();
  ASSERT_TRUE(summary.ok()) << summary.status().message();
  EXPECT_EQ(summary->frames, 2u);

  // PNG colour is lossless: the RGB image comes back exactly.
  const cv::Mat png_color = ReadPng("000000.png");  // stored RGB, read by OpenCV as BGR
  cv::Mat png_rgb;
  cv::cvtColor(png_color, png_rgb, cv::COLOR_BGR2RGB);
  EXPECT_EQ(cv::norm(png_rgb, Gradient(), cv::NORM_INF), 0.0);
  // 16UC1 compressedDepth: the millimetres exactly.
  const cv::Mat depth_mm = ReadPng("000000_depth.png");
  ASSERT_EQ(depth_mm.type(), CV_16UC1);
  EXPECT_EQ(cv::norm(depth_mm, millimetres, cv::NORM_INF), 0.0);

  // JPEG colour: near the orange, in RGB order.
  cv::Mat jpeg_rgb;
  cv::cvtColor(ReadPng("000001.png"), jpeg_rgb, cv::COLOR_BGR2RGB);
  EXPECT_LE(cv::norm(jpeg_rgb, orange, cv::NORM_INF), 3.0);
  // 32FC1 compressedDepth: depth = a / (q - b) in float, as the transport decodes it, in
  // millimetres; within a quantization step (d^2 / a) of the depth encoded; past depth_max
  // and NaN no reading.
  const cv::Mat inverse_mm = ReadPng("000001_depth.png");
  ASSERT_EQ(inverse_mm.type(), CV_16UC1);
  for (int row = 0; row < kHeight; ++row) {
    for (int col = 0; col < kWidth; ++col) {
      const std::uint16_t q = quantized.at<std::uint16_t>(row, col);
      const std::uint16_t got = inverse_mm.at<std::uint16_t>(row, col);
      if (q == 0) {
        EXPECT_EQ(got, 0) << row << "," << col;
        continue;
      }
      const float decoded = inverse.a / (static_cast<float>(q) - inverse.b);
      EXPECT_EQ(got, static_cast<std::uint16_t>(std::round(static_cast<double>(decoded) / 0.001)))
          << row << "," << col;
      const double d = metres.at<float>(row, col);
      EXPECT_NEAR(got * 0.001, d, d * d / inverse.a + 0.0005) << row << "," << col;
    }
  }
  EXPECT_EQ(quantized.at<std::uint16_t>(0, 1), 0);   // the encoder left 12 m out
  EXPECT_EQ(inverse_mm.at<std::uint16_t>(0, 2), 0);  // NaN

  const Result<CameraInfo> camera = ReadCameraYaml(dir_ / "run/camera.yaml");
  ASSERT_TRUE(camera.ok()) << camera.status().message();
  EXPECT_EQ(camera->camera.intrinsics.width, kWidth);
  EXPECT_DOUBLE_EQ(camera->camera.intrinsics.fx, 5.0);
  EXPECT_NEAR(camera->camera.robot_from_camera.translation().z(), 0.3, 1e-12);
}

// A camera as the Neato's records it: JPEG colour on /camera/image_raw/compressed, camera_info
// beside it uncalibrated (size and K zero), no depth, and no tf of the camera's frame.
TEST_F(CompressedImportTest, AnUncalibratedCameraNeedsACameraYaml) {
  WriteBag("", [&](BagWriter& bag) {
    sensor_msgs::CameraInfo uncalibrated;
    uncalibrated.header.stamp = At(1.1);
    uncalibrated.header.frame_id = "/camera_frame";
    ASSERT_TRUE(bag.Write("/camera/camera_info", At(1.1), uncalibrated).ok());
    for (const double t : {1.2, 1.4, 1.6}) {
      ASSERT_TRUE(
          bag.Write("/camera/image_raw/compressed", At(t), CompressedColor(t, Gradient(), "jpeg"))
              .ok());
    }
  });
  const Result<BagImportSummary> refused = Import();
  ASSERT_FALSE(refused.ok());
  EXPECT_THAT(refused.status().message(),
              HasSubstr("/camera/camera_info message 1: camera_info has no calibration"));
  EXPECT_THAT(refused.status().message(), HasSubstr("--camera-yaml"));
  EXPECT_FALSE(fs::exists(dir_ / "run"));

  // The scans alone: no camera wanted, none refused.
  options_.import_camera = false;
  const Result<BagImportSummary> scans_only = Import();
  ASSERT_TRUE(scans_only.ok()) << scans_only.status().message();
  EXPECT_EQ(scans_only->frames, 0u);
  EXPECT_GT(scans_only->scans, 0u);
  EXPECT_FALSE(fs::exists(dir_ / "run/camera.yaml"));
  options_.import_camera = true;

  CameraInfo given;
  given.camera.intrinsics = {kWidth, kHeight, 6.0, 6.0, 3.5, 2.5};
  given.camera.robot_from_camera = CameraMount();
  given.camera.max_range = 4.0;
  ASSERT_TRUE(WriteCameraYaml(dir_ / "given.yaml", given).ok());
  options_.camera_yaml = dir_ / "given.yaml";
  const Result<BagImportSummary> summary = Import();
  ASSERT_TRUE(summary.ok()) << summary.status().message();
  EXPECT_EQ(summary->frames, 3u);
  ASSERT_EQ(summary->warnings.size(), 1u);
  EXPECT_THAT(summary->warnings[0],
              HasSubstr("/camera/image_raw/compressed: colour images without depth"));
  const Result<CameraInfo> camera = ReadCameraYaml(dir_ / "run/camera.yaml");
  ASSERT_TRUE(camera.ok()) << camera.status().message();
  EXPECT_DOUBLE_EQ(camera->camera.intrinsics.fx, 6.0);
  EXPECT_DOUBLE_EQ(camera->camera.max_range, 4.0);
  EXPECT_TRUE(camera->camera.robot_from_camera.isApprox(CameraMount(), 1e-12));
  const cv::Mat depth = ReadPng("000002_depth.png");
  ASSERT_EQ(depth.type(), CV_16UC1);
  EXPECT_EQ(cv::countNonZero(depth), 0);
  EXPECT_EQ(ReadPng("000002.png").size(), cv::Size(kWidth, kHeight));
}

TEST_F(CompressedImportTest, ANamedTopicTheBagLacksIsAnError) {
  WriteBag("", [](BagWriter&) {});
  options_.topics.depth_image = "/front/depth";
  const Result<BagImportSummary> summary = Import();
  ASSERT_FALSE(summary.ok());
  EXPECT_THAT(summary.status().message(),
              HasSubstr("no depth image topic /front/depth (nor /front/depth/compressedDepth)"));
}

TEST(CompressedDepthTest, WhatIsNotReadIsAnErrorNamingTheFormat) {
  const cv::Mat quantized(2, 2, CV_16UC1, cv::Scalar(1000));
  sensor_msgs::CompressedImage msg =
      Compressed(1.0, "32FC1; compressedDepth rvl", DepthPayload(1.0f, 0.0f, quantized));
  EXPECT_THAT(DepthFromCompressedMsg(msg, 0.001).status().message(),
              HasSubstr("only the png codec is read"));
  msg.format = "16UC1; compressedDepth png";
  msg.data.resize(40);  // a truncated PNG
  EXPECT_THAT(DepthFromCompressedMsg(msg, 0.001).status().message(),
              HasSubstr("format '16UC1; compressedDepth png'"));
  msg = Compressed(1.0, "rgb8; jpeg compressed bgr8", Encode(".jpg", cv::Mat(4, 4, CV_8UC3)));
  EXPECT_THAT(DepthFromCompressedMsg(msg, 0.001).status().message(),
              HasSubstr("not a 16-bit single-channel image of millimetres"));
  EXPECT_THAT(
      ColorFromCompressedMsg(Compressed(1.0, "16UC1; compressedDepth", {})).status().message(),
      HasSubstr("is a compressedDepth depth image, not a colour image"));
}

}  // namespace
}  // namespace semchain::ros1
