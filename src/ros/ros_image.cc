#include "ros/ros_image.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <opencv2/imgproc.hpp>

namespace semchain::ros1 {
namespace {

constexpr double kMillimetre = 0.001;

bool IsMillimetres(double depth_scale) { return std::abs(depth_scale - kMillimetre) < 1e-12; }

sensor_msgs::Image ToImageMsg(const cv::Mat& image, const std::string& encoding,
                              const std_msgs::Header& header) {
  sensor_msgs::Image msg;
  msg.header = header;
  msg.height = static_cast<std::uint32_t>(image.rows);
  msg.width = static_cast<std::uint32_t>(image.cols);
  msg.encoding = encoding;
  msg.is_bigendian = std::endian::native == std::endian::big ? 1 : 0;
  msg.step = static_cast<std::uint32_t>(image.cols * image.elemSize());
  msg.data.resize(static_cast<std::size_t>(msg.step) * msg.height);
  for (int row = 0; row < image.rows; ++row) {
    std::memcpy(&msg.data[static_cast<std::size_t>(row) * msg.step], image.ptr(row), msg.step);
  }
  return msg;
}

// The pixels of 'msg' as a Mat of 'type' (a copy, rows packed, in this machine's byte order).
Result<cv::Mat> MatOf(const sensor_msgs::Image& msg, int type) {
  const cv::Mat layout(1, 1, type);
  const std::size_t row_bytes = static_cast<std::size_t>(msg.width) * layout.elemSize();
  if (msg.width == 0 || msg.height == 0 || msg.step < row_bytes ||
      msg.data.size() < static_cast<std::size_t>(msg.step) * msg.height) {
    return Status::Error("image " + std::to_string(msg.width) + "x" + std::to_string(msg.height) +
                         " " + msg.encoding + ": " + std::to_string(msg.data.size()) +
                         " bytes of data do not fill it (step " + std::to_string(msg.step) + ")");
  }
  cv::Mat image(static_cast<int>(msg.height), static_cast<int>(msg.width), type);
  for (int row = 0; row < image.rows; ++row) {
    std::memcpy(image.ptr(row), &msg.data[static_cast<std::size_t>(row) * msg.step], row_bytes);
  }
  const bool swap = (msg.is_bigendian != 0) != (std::endian::native == std::endian::big);
  const std::size_t size = layout.elemSize1();
  if (swap && size > 1) {
    for (int row = 0; row < image.rows; ++row) {
      unsigned char* bytes = image.ptr(row);
      for (std::size_t i = 0; i + size <= row_bytes; i += size) {
        std::reverse(bytes + i, bytes + i + size);
      }
    }
  }
  return image;
}

}  // namespace

sensor_msgs::Image ToColorImageMsg(const cv::Mat& rgb, const std_msgs::Header& header) {
  return ToImageMsg(rgb, "rgb8", header);
}

sensor_msgs::Image ToDepthImageMsg(const cv::Mat& raw, double depth_scale,
                                   const std_msgs::Header& header) {
  if (IsMillimetres(depth_scale)) return ToImageMsg(raw, "16UC1", header);
  cv::Mat metres;
  raw.convertTo(metres, CV_32FC1, depth_scale);
  return ToImageMsg(metres, "32FC1", header);
}

Result<cv::Mat> ColorFromImageMsg(const sensor_msgs::Image& msg) {
  struct Layout {
    const char* encoding;
    int type;
    int conversion;  // to RGB; -1: none
  };
  static constexpr Layout kLayouts[] = {{"rgb8", CV_8UC3, -1},
                                        {"bgr8", CV_8UC3, cv::COLOR_BGR2RGB},
                                        {"rgba8", CV_8UC4, cv::COLOR_RGBA2RGB},
                                        {"bgra8", CV_8UC4, cv::COLOR_BGRA2RGB},
                                        {"mono8", CV_8UC1, cv::COLOR_GRAY2RGB}};
  for (const Layout& layout : kLayouts) {
    if (msg.encoding != layout.encoding) continue;
    Result<cv::Mat> image = MatOf(msg, layout.type);
    if (!image.ok() || layout.conversion < 0) return image;
    cv::Mat rgb;
    cv::cvtColor(*image, rgb, layout.conversion);
    return rgb;
  }
  return Status::Error("colour image encoding '" + msg.encoding +
                       "' is not one of rgb8, bgr8, rgba8, bgra8, mono8");
}

Result<cv::Mat> DepthFromImageMsg(const sensor_msgs::Image& msg, double depth_scale) {
  const bool millimetres = msg.encoding == "16UC1" || msg.encoding == "mono16";
  if (!millimetres && msg.encoding != "32FC1") {
    return Status::Error("depth image encoding '" + msg.encoding +
                         "' is not 16UC1 (mm), mono16 (mm) or 32FC1 (m)");
  }
  Result<cv::Mat> image = MatOf(msg, millimetres ? CV_16UC1 : CV_32FC1);
  if (!image.ok()) return image;
  if (millimetres && IsMillimetres(depth_scale)) return image;
  const double metres_per_value = millimetres ? kMillimetre : 1.0;
  cv::Mat metres;
  image->convertTo(metres, CV_64FC1, metres_per_value);
  return MetresToDepthUnits(metres, depth_scale);
}

cv::Mat MetresToDepthUnits(const cv::Mat& metres, double depth_scale) {
  cv::Mat values;
  metres.convertTo(values, CV_64FC1);  // float readings exactly, NaN and inf kept
  cv::Mat raw(values.size(), CV_16UC1);
  for (int row = 0; row < values.rows; ++row) {
    for (int col = 0; col < values.cols; ++col) {
      const double units = std::round(values.at<double>(row, col) / depth_scale);
      const bool valid = std::isfinite(units) && units > 0.0 && units <= 65535.0;
      raw.at<std::uint16_t>(row, col) = valid ? static_cast<std::uint16_t>(units) : 0;
    }
  }
  return raw;
}

sensor_msgs::CameraInfo ToCameraInfoMsg(const PinholeCamera& camera,
                                        const std_msgs::Header& header) {
  sensor_msgs::CameraInfo msg;
  msg.header = header;
  msg.width = static_cast<std::uint32_t>(camera.width);
  msg.height = static_cast<std::uint32_t>(camera.height);
  msg.distortion_model = "plumb_bob";
  msg.D = {0.0, 0.0, 0.0, 0.0, 0.0};
  msg.K = {camera.fx, 0.0, camera.cx, 0.0, camera.fy, camera.cy, 0.0, 0.0, 1.0};
  msg.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  msg.P = {camera.fx, 0.0, camera.cx, 0.0, 0.0, camera.fy, camera.cy, 0.0, 0.0, 0.0, 1.0, 0.0};
  return msg;
}

Result<PinholeCamera> FromCameraInfoMsg(const sensor_msgs::CameraInfo& msg, bool* has_distortion) {
  PinholeCamera camera;
  camera.width = static_cast<int>(msg.width);
  camera.height = static_cast<int>(msg.height);
  camera.fx = msg.K[0];
  camera.fy = msg.K[4];
  camera.cx = msg.K[2];
  camera.cy = msg.K[5];
  if (camera.width <= 0 || camera.height <= 0 || !(camera.fx > 0.0) || !(camera.fy > 0.0)) {
    return Status::Error("camera_info has no calibration (size " + std::to_string(msg.width) + "x" +
                         std::to_string(msg.height) + ", fx " + std::to_string(camera.fx) +
                         ", fy " + std::to_string(camera.fy) + ")");
  }
  *has_distortion = std::any_of(msg.D.begin(), msg.D.end(), [](double d) { return d != 0.0; });
  return camera;
}

}  // namespace semchain::ros1
