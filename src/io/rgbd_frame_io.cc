#include "io/rgbd_frame_io.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <system_error>

namespace semchain {
namespace fs = std::filesystem;
namespace {

Status CheckReadable(const fs::path& path) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) {
    return Status::Error(path.string() + ": no such image file");
  }
  return Status::Ok();
}

}  // namespace

fs::path ColorImagePath(const fs::path& run_dir, const std::string& frame) {
  return run_dir / (frame + ".png");
}

fs::path DepthImagePath(const fs::path& run_dir, const std::string& frame) {
  return run_dir / (frame + "_depth.png");
}

Result<cv::Mat> ReadColorImage(const fs::path& path) {
  SEMCHAIN_RETURN_IF_ERROR(CheckReadable(path));
  cv::Mat bgr = cv::imread(path.string(), cv::IMREAD_COLOR);
  if (bgr.empty()) return Status::Error(path.string() + ": cannot decode image");
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  return rgb;
}

Result<cv::Mat> ReadDepthImage(const fs::path& path, double depth_scale, cv::Size expected_size) {
  SEMCHAIN_RETURN_IF_ERROR(CheckReadable(path));
  cv::Mat raw = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  if (raw.empty()) return Status::Error(path.string() + ": cannot decode image");
  if (raw.type() != CV_16UC1) {
    return Status::Error(path.string() + ": expected a single-channel 16-bit depth image");
  }
  if (!expected_size.empty() && raw.size() != expected_size) {
    return Status::Error(path.string() + ": depth image is " + std::to_string(raw.cols) + "x" +
                         std::to_string(raw.rows) + ", the camera is " +
                         std::to_string(expected_size.width) + "x" +
                         std::to_string(expected_size.height));
  }
  cv::Mat metres;
  raw.convertTo(metres, CV_32FC1, depth_scale);
  return metres;
}

}  // namespace semchain
