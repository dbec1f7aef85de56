#pragma once

#include "sensors/detection.h"

// Detections written out in tests of the metrics.
namespace semchain::detection::testing {

inline Detection Predicted(int class_id, double score, double x1, double y1, double x2, double y2) {
  Detection d;
  d.class_id = class_id;
  d.score = score;
  d.box[0] = x1, d.box[1] = y1, d.box[2] = x2, d.box[3] = y2;
  return d;
}

}  // namespace semchain::detection::testing
