#pragma once

#include <string>
#include <vector>

namespace semchain {

// One object found in a camera frame (DESIGN.md §5.5).
struct Detection {
  std::string class_name;
  int class_id = -1;
  double score = 0.0;
  double box[4] = {0.0, 0.0, 0.0, 0.0};  // x1, y1, x2, y2 in image pixels
  double depth_m = 0.0;                  // depth of the visible surface at the box
};

// The detections of one frame; 'frame' names the RGB/depth pair without extension.
struct FrameDetections {
  std::string frame;
  double stamp = 0.0;
  std::vector<Detection> detections;
};

// The default class list and order: the ten classes of seed 000's data set (§2.1), whose first
// five are the order of its class-count vectors (§3.1 step 4).
inline const std::vector<std::string>& DefaultClassNames() {
  static const std::vector<std::string> kNames = {"door",  "cabinet", "bucket",   "chair", "stool",
                                                  "table", "sofa",    "computer", "bed",   "clock"};
  return kNames;
}

}  // namespace semchain
