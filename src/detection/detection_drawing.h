#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "sensors/detection.h"

namespace semchain::detection {

// A copy of 'image' (CV_8UC3, RGB) with each detection's box outlined in its class's colour
// and labelled "class score" (and the depth when it has one; only "class" when the score is
// negative, as for truth boxes).
cv::Mat DrawDetections(const cv::Mat& image, const std::vector<Detection>& detections);

}  // namespace semchain::detection
