#include "io/camera_io.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "io/rgbd_frame_io.h"

namespace semchain {
namespace {

namespace fs = std::filesystem;

fs::path TempPath(const std::string& name) { return fs::path(testing::TempDir()) / name; }

CameraInfo PitchedCamera() {
  CameraInfo info;
  info.camera.intrinsics = PinholeCamera::FromFov(320, 240, 60.0 * M_PI / 180.0);
  info.camera.max_range = 5.5;
  info.depth_scale = 0.001;
  info.frame_rate_hz = 4.0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()) *
                   Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  pose.translation() = Eigen::Vector3d(0.12, -0.01, 0.5);
  info.camera.robot_from_camera = pose;
  return info;
}

TEST(CameraIoTest, RoundTrip) {
  const CameraInfo info = PitchedCamera();
  const fs::path path = TempPath("camera.yaml");
  ASSERT_TRUE(WriteCameraYaml(path, info).ok());
  Result<CameraInfo> read = ReadCameraYaml(path);
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(read->camera.intrinsics.width, 320);
  EXPECT_EQ(read->camera.intrinsics.height, 240);
  EXPECT_NEAR(read->camera.intrinsics.fx, info.camera.intrinsics.fx, 1e-6);
  EXPECT_NEAR(read->camera.intrinsics.cy, info.camera.intrinsics.cy, 1e-9);
  EXPECT_DOUBLE_EQ(read->camera.max_range, 5.5);
  EXPECT_DOUBLE_EQ(read->frame_rate_hz, 4.0);
  EXPECT_TRUE(read->camera.robot_from_camera.isApprox(info.camera.robot_from_camera, 1e-8));
}

TEST(CameraIoTest, RejectsARotationThatIsNotOne) {
  const fs::path path = TempPath("bad_camera.yaml");
  std::ofstream(path) << "width: 320\nheight: 240\nfx: 277\nfy: 277\ncx: 159.5\ncy: 119.5\n"
                         "max_range: 6\ndepth_scale: 0.001\n"
                         "robot_from_camera:\n  translation: [0, 0, 0.5]\n"
                         "  rotation: [[1, 0, 0], [0, 2, 0], [0, 0, 1]]\n";
  Result<CameraInfo> read = ReadCameraYaml(path);
  ASSERT_FALSE(read.ok());
  EXPECT_NE(read.status().message().find("bad_camera.yaml:11: robot_from_camera.rotation"),
            std::string::npos)
      << read.status().message();
}

TEST(CameraIoTest, RejectsAMissingIntrinsic) {
  const fs::path path = TempPath("no_fx.yaml");
  std::ofstream(path) << "width: 320\nheight: 240\nfy: 277\ncx: 159.5\ncy: 119.5\n"
                         "max_range: 6\ndepth_scale: 0.001\n"
                         "robot_from_camera:\n  translation: [0, 0, 0.5]\n"
                         "  rotation: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\n";
  Result<CameraInfo> read = ReadCameraYaml(path);
  ASSERT_FALSE(read.ok());
  EXPECT_NE(read.status().message().find("fx: missing"), std::string::npos)
      << read.status().message();
}

TEST(RgbdFrameIoTest, DepthIsScaledToMetresAndChecked) {
  cv::Mat raw(4, 6, CV_16UC1, cv::Scalar(0));
  raw.at<std::uint16_t>(1, 2) = 2310;
  const fs::path path = TempPath("000001_depth.png");
  ASSERT_TRUE(cv::imwrite(path.string(), raw));
  Result<cv::Mat> depth = ReadDepthImage(path, 0.001, cv::Size(6, 4));
  ASSERT_TRUE(depth.ok()) << depth.status().message();
  EXPECT_FLOAT_EQ(depth->at<float>(1, 2), 2.31f);
  EXPECT_FLOAT_EQ(depth->at<float>(0, 0), 0.0f);
  EXPECT_FALSE(ReadDepthImage(path, 0.001, cv::Size(320, 240)).ok());

  cv::Mat colour(4, 6, CV_8UC3, cv::Scalar(1, 2, 3));
  const fs::path colour_path = TempPath("000001.png");
  ASSERT_TRUE(cv::imwrite(colour_path.string(), colour));
  EXPECT_FALSE(ReadDepthImage(colour_path, 0.001).ok());
  Result<cv::Mat> rgb = ReadColorImage(colour_path);
  ASSERT_TRUE(rgb.ok());
  EXPECT_EQ(rgb->at<cv::Vec3b>(0, 0), cv::Vec3b(3, 2, 1));  // written BGR, read RGB
  EXPECT_FALSE(ReadColorImage(TempPath("missing.png")).ok());
}

}  // namespace
}  // namespace semchain
