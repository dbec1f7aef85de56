#pragma once

#include <vector>

#include "detection/yolo_head.h"

namespace semchain::detection {

// Class-wise non-maximum suppression: among candidates of the same class, a box that overlaps a
// better-scoring kept box by an IoU above 'iou_threshold' is dropped; boxes of different classes
// never suppress each other. Returns the indices of the kept candidates, best score first
// (ties: lower index first), at most 'max_count' of them.
std::vector<int> ClassWiseNms(const std::vector<Candidate>& candidates, double iou_threshold,
                              int max_count);

}  // namespace semchain::detection
