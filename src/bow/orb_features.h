#pragma once

#include <opencv2/core.hpp>
#include <string>

// ORB features of a camera frame for the bag of words (seed 000 §3.1 step 1; Rublee et al.
// 2011, through OpenCV's cv::ORB).
namespace semchain::bow {

struct OrbOptions {
  int max_features = 500;     // strongest FAST corners kept (by Harris score)
  double scale_factor = 1.2;  // between pyramid levels
  int pyramid_levels = 8;
  int fast_threshold = 20;  // intensity difference of a FAST corner (0–255)
  bool Validate(std::string* error) const;
};

// The 32-byte ORB descriptors (CV_8UC1, one row per keypoint; empty when none) of an 8-bit
// grey, RGB or BGR image (colour is converted to grey; RGB and BGR give almost the same grey).
cv::Mat ExtractOrbDescriptors(const cv::Mat& image, const OrbOptions& options);

}  // namespace semchain::bow
