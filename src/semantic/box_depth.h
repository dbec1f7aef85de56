#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "sensors/camera.h"
#include "sensors/detection.h"

// A depth image made from detections alone, for frames that come without one (the ROS node fed
// /semchain/detections, a bag exported without images): each box is filled with its
// detection's depth, nearer boxes over farther ones. The mapper then sees each object as a
// surface across its box at the measured range, and free space up to it.
namespace semchain::semantic {

// CV_32FC1 of the camera's size, metres, 0 outside the boxes (no reading).
cv::Mat DepthFromBoxes(const std::vector<Detection>& detections, const PinholeCamera& camera);

}  // namespace semchain::semantic
