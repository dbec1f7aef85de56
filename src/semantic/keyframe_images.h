#pragma once

#include <cstddef>
#include <deque>
#include <filesystem>
#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/status.h"
#include "semantic/keyframes.h"

// The colour images of the frames a live semantic mapper used, kept PNG-encoded in memory so
// that a map folder saved where no run folder exists (the ROS node's mapping mode) still holds
// its keyframes' images, which the bag-of-words stage (seed 000 §3.1 step 3) describes. A frame
// whose detector ran on the image has it at hand; detection records arriving on their own topic
// are paired with the camera's images by stamp, in whichever order the two arrive.
namespace semchain::semantic {

struct KeyframeImageOptions {
  // An image and a detection record this close in time are the same camera frame (records
  // carry the image's own stamp; the tolerance only absorbs rounding).
  double stamp_tolerance_s = 1e-3;
  // Unpaired images and records waiting for their partner: about a second of a 30 Hz camera.
  std::size_t pending = 30;
  // PNG compression 0..9: 1 encodes a 640 × 480 image in a few milliseconds at ~1.2× the size
  // of level 9; the images are lossless either way, so the bag-of-words words are the same.
  int png_compression = 1;
};

class KeyframeImages {
 public:
  explicit KeyframeImages(KeyframeImageOptions options = {});

  // 'frame''s colour image (CV_8UC3, RGB order), e.g. the image the detector ran on.
  void AddFrameImage(const std::string& frame, const cv::Mat& rgb);
  // A camera image (RGB) and a detection record, paired by stamp.
  void AddImage(double stamp, const cv::Mat& rgb);
  void AddFrame(const std::string& frame, double stamp);

  bool Has(const std::string& frame) const { return encoded_.count(frame) > 0; }
  std::size_t size() const { return encoded_.size(); }
  std::size_t bytes() const { return bytes_; }

  // Writes dir/<frame>.png (the layout of io/rgbd_frame_io.h) for every keyframe with an
  // image, and returns those keyframes; keyframes without an image are left out (the
  // bag-of-words stage cannot describe them). An unwritable file is an error naming it.
  Result<std::vector<Keyframe>> Write(const std::filesystem::path& dir,
                                      const std::vector<Keyframe>& keyframes) const;

 private:
  struct PendingImage {
    double stamp = 0.0;
    cv::Mat rgb;
  };
  struct PendingFrame {
    double stamp = 0.0;
    std::string frame;
  };

  void Keep(const std::string& frame, const cv::Mat& rgb);

  KeyframeImageOptions options_;
  std::map<std::string, std::vector<unsigned char>> encoded_;  // frame → PNG bytes (BGR file)
  std::size_t bytes_ = 0;
  std::deque<PendingImage> images_;
  std::deque<PendingFrame> frames_;
};

}  // namespace semchain::semantic
