#pragma once

#include <vector>

#include "detection/detection_metrics.h"
#include "sensors/detection.h"

// What a detector calls each labelled object (ultralytics' confusion matrix): detections at or
// above a confidence are paired one to one with the labelled boxes they overlap, whatever
// their classes, largest IoU first. mAP says how well a detector ranks its boxes; this says
// which names it mixes up, which a semantic map inherits (a sofa the size of a bed named a bed).
namespace semchain::detection {

struct ConfusionOptions {
  double min_score = 0.25;  // detections below it are not counted (ultralytics' default)
  double min_iou = 0.45;    // a detection and a labelled box overlapping less are not a pair
};

class ConfusionMatrix {
 public:
  ConfusionMatrix(int class_count, const ConfusionOptions& options = {});

  void AddImage(const std::vector<Detection>& detections, const std::vector<TruthBox>& truths);

  int class_count() const { return class_count_; }
  // Labelled objects of class 'truth' that the detector named 'detected'; 'detected' ==
  // class_count(): missed (no detection paired with it).
  int Count(int truth, int detected) const { return counts_[truth][detected]; }
  // Detections of class 'detected' paired with no labelled object.
  int Unpaired(int detected) const { return counts_[class_count_][detected]; }

 private:
  int class_count_;
  ConfusionOptions options_;
  std::vector<std::vector<int>> counts_;  // (classes + 1) × (classes + 1)
};

}  // namespace semchain::detection
