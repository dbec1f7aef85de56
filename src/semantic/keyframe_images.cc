#include "semantic/keyframe_images.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string_view>

#include "core/atomic_file.h"
#include "io/rgbd_frame_io.h"

namespace semchain::semantic {

KeyframeImages::KeyframeImages(KeyframeImageOptions options) : options_(options) {}

void KeyframeImages::Keep(const std::string& frame, const cv::Mat& rgb) {
  if (rgb.empty() || Has(frame)) return;
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", bgr, png, {cv::IMWRITE_PNG_COMPRESSION, options_.png_compression})) {
    return;
  }
  bytes_ += png.size();
  encoded_.emplace(frame, std::move(png));
}

void KeyframeImages::AddFrameImage(const std::string& frame, const cv::Mat& rgb) {
  Keep(frame, rgb);
}

void KeyframeImages::AddImage(double stamp, const cv::Mat& rgb) {
  const auto same = [&](const PendingFrame& pending) {
    return std::abs(pending.stamp - stamp) <= options_.stamp_tolerance_s;
  };
  const auto waiting = std::find_if(frames_.begin(), frames_.end(), same);
  if (waiting != frames_.end()) {
    Keep(waiting->frame, rgb);
    frames_.erase(waiting);
    return;
  }
  // A clone: the caller's buffer (a ROS message's) is reused after the callback.
  images_.push_back({stamp, rgb.clone()});
  while (images_.size() > options_.pending) images_.pop_front();
}

void KeyframeImages::AddFrame(const std::string& frame, double stamp) {
  const auto same = [&](const PendingImage& pending) {
    return std::abs(pending.stamp - stamp) <= options_.stamp_tolerance_s;
  };
  const auto waiting = std::find_if(images_.begin(), images_.end(), same);
  if (waiting != images_.end()) {
    Keep(frame, waiting->rgb);
    images_.erase(waiting);
    return;
  }
  frames_.push_back({stamp, frame});
  while (frames_.size() > options_.pending) frames_.pop_front();
}

Result<std::vector<Keyframe>> KeyframeImages::Write(const std::filesystem::path& dir,
                                                    const std::vector<Keyframe>& keyframes) const {
  std::vector<Keyframe> written;
  for (const Keyframe& keyframe : keyframes) {
    const auto image = encoded_.find(keyframe.frame);
    if (image == encoded_.end()) continue;
    const std::filesystem::path path = ColorImagePath(dir, keyframe.frame);
    std::error_code error;
    std::filesystem::create_directories(path.parent_path(), error);
    if (error) return Status::Error(path.parent_path().string() + ": " + error.message());
    const std::vector<unsigned char>& png = image->second;
    SEMCHAIN_RETURN_IF_ERROR(WriteFileAtomically(
        path, std::string_view(reinterpret_cast<const char*>(png.data()), png.size())));
    written.push_back(keyframe);
  }
  return written;
}

}  // namespace semchain::semantic
