#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "detection/confusion_matrix.h"
#include "detection/detection_metrics.h"
#include "detection/detector.h"
#include "detection/yolo_dataset.h"

// `semchain bench detector` (seed 000 Table 2): a detector run over a data set split, scored
// against its labels (detection_metrics.h) and timed per frame.
namespace semchain::detection {

struct DetectorBenchmark {
  int images = 0;
  int truths = 0;
  DetectionAccuracy accuracy;
  ConfusionMatrix confusion{0};  // sized to the data set's classes
  double mean_ms = 0.0;          // wall time of Detect per frame
  double median_ms = 0.0;
};

// Runs 'detector' on every image of 'split', its label file read with the data set's class
// count (a label line out of range is an error naming file and line). The detector's class
// names must be the data set's. 'progress' gets the images done.
Result<DetectorBenchmark> BenchmarkDetector(Detector& detector, const YoloDataset& dataset,
                                            const std::string& split,
                                            const std::function<void(int, int)>& progress = {},
                                            const ConfusionOptions& confusion = {});

}  // namespace semchain::detection
