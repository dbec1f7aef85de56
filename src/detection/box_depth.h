#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string>

// The depth of a detection from the depth frame aligned with its colour frame, measured the way
// the simulator reports it (the median depth of the object's visible pixels, see
// sim/detection_model.h): a box also holds background, so only its core is used.
namespace semchain::detection {

struct BoxDepthOptions {
  // The central part of the box whose pixels count, as a fraction of its width and height.
  double core_fraction = 0.5;
  // At least this fraction of the core's pixels must have a depth reading, or the box has no
  // depth (the simulator likewise reports only objects most of whose pixels are measured).
  double min_valid_fraction = 0.5;

  bool Validate(std::string* error) const;
};

// The median of the valid depths (finite and > 0, metres) of the pixels whose centres lie in
// the core of 'box' ([x1, y1, x2, y2], pixel-edge coordinates) of 'depth_m' (CV_32FC1); at least
// the pixel under the box centre is used. std::nullopt when the box lies outside the image or
// too few of its core's pixels have a depth. For an even count the upper median is taken.
std::optional<double> BoxDepth(const cv::Mat& depth_m, const double box[4],
                               const BoxDepthOptions& options);

}  // namespace semchain::detection
