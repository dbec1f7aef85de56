#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/status.h"
#include "sensors/detection.h"

// The object detector interface (DESIGN.md §3.10): the YOLOv8-format ONNX detector implements
// it, and the simulator's truth-based model can sit behind it too.
namespace semchain::detection {

class Detector {
 public:
  virtual ~Detector() = default;

  // The objects in 'rgb' (CV_8UC3 in RGB order, as ReadColorImage returns it): class, score
  // and box [x1, y1, x2, y2] in pixel-edge coordinates of 'rgb' (pixel (u, v) spans
  // [u, u + 1) × [v, v + 1)), best score first. depth_m is left 0: the detector sees no depth
  // (box_depth.h measures it). An error when 'rgb' is unusable or the model fails.
  virtual Result<std::vector<Detection>> Detect(const cv::Mat& rgb) = 0;

  // The class names, indexed by Detection::class_id.
  virtual const std::vector<std::string>& class_names() const = 0;
};

}  // namespace semchain::detection
