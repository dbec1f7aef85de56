#pragma once

#include <array>
#include <vector>

#include "sensors/detection.h"

// Detection accuracy as the YOLO literature reports it (seed 000 Table 2): average precision
// per class at IoU thresholds 0.50, 0.55, …, 0.95 (COCO), mAP@0.5 and mAP@0.5:0.95 over the
// classes that have ground truth, and precision and recall at the confidence that maximises
// their mean F1 (what ultralytics prints).
namespace semchain::detection {

struct TruthBox {
  int class_id = 0;
  std::array<double, 4> box = {0.0, 0.0, 0.0, 0.0};  // x1, y1, x2, y2 in pixels
};

// A detection's box as the metrics take it.
inline std::array<double, 4> BoxOf(const Detection& detection) {
  return {detection.box[0], detection.box[1], detection.box[2], detection.box[3]};
}

// Intersection over union of two [x1, y1, x2, y2] boxes (0 when either is empty).
double BoxIou(const std::array<double, 4>& a, const std::array<double, 4>& b);

// The area under the precision envelope of a precision/recall curve (points sorted by
// decreasing score), sampled at 101 recall values from 0 to 1 (COCO's interpolation).
double AveragePrecision(const std::vector<double>& recall, const std::vector<double>& precision);

struct ClassAccuracy {
  int truths = 0;
  double ap50 = 0.0;
  double ap50_95 = 0.0;
};

struct DetectionAccuracy {
  double map50 = 0.0;
  double map50_95 = 0.0;
  double precision = 0.0;  // at the confidence of the best mean F1
  double recall = 0.0;
  double confidence = 0.0;  // that confidence
  std::vector<ClassAccuracy> classes;
};

// Accumulates images: their detections and their ground truth.
class DetectionEvaluator {
 public:
  explicit DetectionEvaluator(int class_count);

  // One image. A detection matches the unmatched truth of its class with the highest IoU at or
  // above each threshold, best-scoring detections first (greedy, as COCO and ultralytics do).
  void AddImage(const std::vector<Detection>& detections, const std::vector<TruthBox>& truths);

  DetectionAccuracy Evaluate() const;

 private:
  static constexpr int kThresholds = 10;  // IoU 0.50 … 0.95
  struct Scored {
    double score;
    std::array<bool, kThresholds> true_positive;
  };
  int class_count_;
  std::vector<std::vector<Scored>> scored_;  // per class
  std::vector<int> truths_;                  // per class
};

}  // namespace semchain::detection
