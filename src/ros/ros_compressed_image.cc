#include "ros/ros_compressed_image.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "ros/ros_image.h"

namespace semchain::ros1 {
namespace {

constexpr double kMetresPerMillimetre = 0.001;
// compressed_depth_image_transport's ConfigHeader: int32 format, float32 depthParam[2].
constexpr std::size_t kDepthHeaderBytes = 12;

bool Contains(const std::string& text, const char* part) {
  return text.find(part) != std::string::npos;
}

// The image encoding that 'format' names before its ';' ("32FC1; compressedDepth png"), empty
// when it has none.
std::string EncodingOf(const std::string& format) {
  const std::size_t semicolon = format.find(';');
  if (semicolon == std::string::npos) return "";
  std::string encoding = format.substr(0, semicolon);
  while (!encoding.empty() && encoding.back() == ' ') encoding.pop_back();
  while (!encoding.empty() && encoding.front() == ' ') encoding.erase(encoding.begin());
  return encoding;
}

// The image in 'msg.data' from byte 'offset' on (cv::imdecode with 'flags').
Result<cv::Mat> Decode(const sensor_msgs::CompressedImage& msg, std::size_t offset, int flags) {
  if (msg.data.size() <= offset) {
    return Status::Error("compressed image (format '" + msg.format +
                         "'): " + std::to_string(msg.data.size()) + " bytes, no image data");
  }
  const cv::Mat bytes(1, static_cast<int>(msg.data.size() - offset), CV_8UC1,
                      const_cast<std::uint8_t*>(msg.data.data() + offset));
  cv::Mat image;
  try {
    image = cv::imdecode(bytes, flags);
  } catch (const cv::Exception& error) {
    return Status::Error("compressed image (format '" + msg.format +
                         "') does not decode: " + error.what());
  }
  if (image.empty()) {
    return Status::Error("compressed image (format '" + msg.format +
                         "'): its data is no image OpenCV reads");
  }
  return image;
}

// 16-bit millimetres in 'depth_scale' units.
cv::Mat FromMillimetres(const cv::Mat& millimetres, double depth_scale) {
  if (std::abs(depth_scale - kMetresPerMillimetre) < 1e-12) return millimetres;
  cv::Mat metres;
  millimetres.convertTo(metres, CV_64FC1, kMetresPerMillimetre);
  return MetresToDepthUnits(metres, depth_scale);
}

Result<cv::Mat> FromCompressedDepth(const sensor_msgs::CompressedImage& msg, double depth_scale) {
  const std::string& format = msg.format;
  const std::size_t codec = format.find("compressedDepth");
  const std::string after = format.substr(codec + std::string("compressedDepth").size());
  if (!after.empty() && after != " png") {
    return Status::Error("compressedDepth image (format '" + format +
                         "'): only the png codec is read");
  }
  const std::string encoding = EncodingOf(format);
  const bool inverse_depth = encoding == "32FC1";
  if (!inverse_depth && encoding != "16UC1" && encoding != "mono16") {
    return Status::Error("compressedDepth image (format '" + format + "'): encoding '" + encoding +
                         "' is not 16UC1 (mm) or 32FC1 (m)");
  }
  Result<cv::Mat> quantized = Decode(msg, kDepthHeaderBytes, cv::IMREAD_UNCHANGED);
  if (!quantized.ok()) return quantized;
  if (quantized->type() != CV_16UC1) {
    return Status::Error("compressedDepth image (format '" + format +
                         "'): its PNG is not single-channel 16-bit");
  }
  if (!inverse_depth) return FromMillimetres(*quantized, depth_scale);
  float depth_param[2];
  std::memcpy(depth_param, msg.data.data() + 4, sizeof(depth_param));
  // As compressed_depth_image_transport decodes it, in float: depth = a / (q - b); q = 0 is no
  // reading.
  const float a = depth_param[0];
  const float b = depth_param[1];
  cv::Mat metres(quantized->size(), CV_32FC1);
  for (int row = 0; row < metres.rows; ++row) {
    const std::uint16_t* q = quantized->ptr<std::uint16_t>(row);
    float* depth = metres.ptr<float>(row);
    for (int col = 0; col < metres.cols; ++col) {
      depth[col] = q[col] == 0 ? std::numeric_limits<float>::quiet_NaN()
                               : a / (static_cast<float>(q[col]) - b);
    }
  }
  return MetresToDepthUnits(metres, depth_scale);
}

}  // namespace

Result<cv::Mat> ColorFromCompressedMsg(const sensor_msgs::CompressedImage& msg) {
  if (Contains(msg.format, "compressedDepth")) {
    return Status::Error("compressed image (format '" + msg.format +
                         "') is a compressedDepth depth image, not a colour image");
  }
  Result<cv::Mat> image = Decode(msg, 0, cv::IMREAD_COLOR);
  if (!image.ok()) return image;
  // compressed_image_transport encodes colour as bgr8 (OpenCV's order, which imdecode gives
  // back); a format saying the bytes are rgb holds them the other way round.
  if (Contains(msg.format, "compressed rgb")) return image;
  cv::Mat rgb;
  cv::cvtColor(*image, rgb, cv::COLOR_BGR2RGB);
  return rgb;
}

Result<cv::Mat> DepthFromCompressedMsg(const sensor_msgs::CompressedImage& msg,
                                       double depth_scale) {
  if (Contains(msg.format, "compressedDepth")) return FromCompressedDepth(msg, depth_scale);
  Result<cv::Mat> image = Decode(msg, 0, cv::IMREAD_UNCHANGED);
  if (!image.ok()) return image;
  if (image->type() != CV_16UC1) {
    return Status::Error("compressed depth image (format '" + msg.format +
                         "') is not a 16-bit single-channel image of millimetres (record depth "
                         "with compressed_depth_image_transport: the compressedDepth topic)");
  }
  return FromMillimetres(*image, depth_scale);
}

}  // namespace semchain::ros1
