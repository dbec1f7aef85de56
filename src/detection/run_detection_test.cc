#include "detection/run_detection.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "detection/testing/square_scene.h"
#include "detection/yolo_detector.h"
#include "io/detections_io.h"

namespace semchain::detection {
namespace {

namespace fs = std::filesystem;
using testing::SceneSquares;
using testing::Square;
using testing::SquareClasses;
using testing::SquareImage;
using testing::TestModel;

// A run directory with two frames of SceneSquares(): each square stands at its own depth except
// the green one, which the depth camera does not measure.
class RunDetectionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    run_ =
        fs::temp_directory_path() / ("semchain_run_detection_test_" + std::to_string(::getpid()));
    fs::remove_all(run_);
    fs::create_directories(run_ / "frames");
    CameraInfo camera;
    camera.camera.intrinsics.width = 640;
    camera.camera.intrinsics.height = 480;
    camera.frame_rate_hz = 4.0;
    ASSERT_TRUE(WriteCameraYaml(run_ / "camera.yaml", camera).ok());
    const std::vector<Square> squares = SceneSquares();
    cv::Mat bgr;
    cv::cvtColor(SquareImage(squares), bgr, cv::COLOR_RGB2BGR);
    cv::Mat depth(480, 640, CV_16UC1, cv::Scalar(4000));  // the wall behind, 4 m
    const std::uint16_t depth_mm[4] = {1500, 0, 2250, 3000};
    for (std::size_t i = 0; i < squares.size(); ++i) depth(squares[i].rect).setTo(depth_mm[i]);
    for (const char* name : {"000000", "000001"}) {
      ASSERT_TRUE(cv::imwrite((run_ / "frames" / (std::string(name) + ".png")).string(), bgr));
      ASSERT_TRUE(
          cv::imwrite((run_ / "frames" / (std::string(name) + "_depth.png")).string(), depth));
    }
    // The simulator records frame times in detections.jsonl; frame 1 is not listed there.
    ASSERT_TRUE(
        WriteDetectionsJsonl(run_ / "detections.jsonl", {{"frames/000000", 7.25, {}}}).ok());
    YoloOptions options;
    options.input_width = 320;
    options.input_height = 256;
    Result<std::unique_ptr<YoloDetector>> detector =
        YoloDetector::Load(TestModel("tiny_squares_raw.onnx"), SquareClasses(), options);
    ASSERT_TRUE(detector.ok()) << detector.status().message();
    detector_ = std::move(*detector);
  }
  void TearDown() override { fs::remove_all(run_); }

  fs::path run_;
  std::unique_ptr<YoloDetector> detector_;
};

TEST_F(RunDetectionTest, DetectsEveryFrameWithDepthsAndSimulatorNames) {
  ASSERT_TRUE(IsRunDirectory(run_));
  int sunk = 0;
  Result<std::vector<FrameDetections>> frames = DetectRunFrames(
      *detector_, run_, RunDetectionOptions(), [&sunk](const cv::Mat& rgb, const FrameDetections&) {
        EXPECT_EQ(rgb.at<cv::Vec3b>(50, 50), cv::Vec3b(255, 0, 0));  // red, in RGB order
        ++sunk;
        return Status::Ok();
      });
  ASSERT_TRUE(frames.ok()) << frames.status().message();
  EXPECT_EQ(sunk, 2);
  ASSERT_EQ(frames->size(), 2u);
  EXPECT_EQ((*frames)[0].frame, "frames/000000");
  EXPECT_EQ((*frames)[0].stamp, 7.25);
  EXPECT_EQ((*frames)[1].frame, "frames/000001");
  EXPECT_EQ((*frames)[1].stamp, 0.25);  // 1 / frame_rate_hz
  for (const FrameDetections& frame : *frames) {
    // The green square has no depth reading: dropped, as the simulator drops such objects.
    ASSERT_EQ(frame.detections.size(), 3u);
    for (const Detection& d : frame.detections) {
      const double expected = d.class_id == 2 ? 2.25 : (d.box[0] < 100 ? 1.5 : 3.0);
      EXPECT_NEAR(d.depth_m, expected, 1e-6) << d.class_name << " at " << d.box[0];
    }
  }
}

TEST_F(RunDetectionTest, KeepsDetectionsWithoutDepthWhenAsked) {
  RunDetectionOptions options;
  options.keep_without_depth = true;
  Result<std::vector<FrameDetections>> frames = DetectRunFrames(*detector_, run_, options);
  ASSERT_TRUE(frames.ok()) << frames.status().message();
  ASSERT_EQ((*frames)[0].detections.size(), 4u);
  int without = 0;
  for (const Detection& d : (*frames)[0].detections) without += d.depth_m == 0.0;
  EXPECT_EQ(without, 1);
}

TEST_F(RunDetectionTest, NamesAMissingDepthFrame) {
  fs::remove(run_ / "frames" / "000001_depth.png");
  Result<std::vector<FrameDetections>> frames = DetectRunFrames(*detector_, run_);
  ASSERT_FALSE(frames.ok());
  EXPECT_EQ(frames.status().message(),
            (run_ / "frames" / "000001_depth.png").string() + ": no such image file");
}

}  // namespace
}  // namespace semchain::detection
