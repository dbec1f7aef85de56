#include "bow/orb_features.h"

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/check.h"

namespace semchain::bow {

bool OrbOptions::Validate(std::string* error) const {
  if (max_features < 1) {
    *error = "max_features must be at least 1, got " + std::to_string(max_features);
    return false;
  }
  if (!(scale_factor > 1.0) || pyramid_levels < 1 || fast_threshold < 1) {
    *error = "scale_factor must exceed 1, pyramid_levels and fast_threshold be at least 1";
    return false;
  }
  return true;
}

cv::Mat ExtractOrbDescriptors(const cv::Mat& image, const OrbOptions& options) {
  SEMCHAIN_CHECK(image.depth() == CV_8U && (image.channels() == 1 || image.channels() == 3));
  cv::Mat grey = image;
  if (image.channels() == 3) cv::cvtColor(image, grey, cv::COLOR_RGB2GRAY);
  cv::Ptr<cv::ORB> orb = cv::ORB::create(
      options.max_features, static_cast<float>(options.scale_factor), options.pyramid_levels, 31, 0,
      2, cv::ORB::HARRIS_SCORE, 31, options.fast_threshold);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  orb->detectAndCompute(grey, cv::noArray(), keypoints, descriptors);
  return descriptors;
}

}  // namespace semchain::bow
