#include "detection/detector_benchmark.h"

#include <algorithm>
#include <chrono>
#include <numeric>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/yolo_labels.h"

namespace semchain::detection {
namespace fs = std::filesystem;

Result<DetectorBenchmark> BenchmarkDetector(Detector& detector, const YoloDataset& dataset,
                                            const std::string& split,
                                            const std::function<void(int, int)>& progress,
                                            const ConfusionOptions& confusion) {
  if (detector.class_names() != dataset.names) {
    return Status::Error("the model's classes (" + std::to_string(detector.class_names().size()) +
                         ") are not the data set's (" + std::to_string(dataset.names.size()) +
                         ", in data.yaml's order)");
  }
  Result<std::vector<fs::path>> images = SplitImages(dataset, split);
  if (!images.ok()) return images.status();
  DetectorBenchmark result;
  DetectionEvaluator evaluator(static_cast<int>(dataset.names.size()));
  result.confusion = ConfusionMatrix(static_cast<int>(dataset.names.size()), confusion);
  std::vector<double> times_ms;
  for (const fs::path& path : *images) {
    const cv::Mat bgr = cv::imread(path.string(), cv::IMREAD_COLOR);
    if (bgr.empty()) return Status::Error(path.string() + ": cannot read the image");
    cv::Mat rgb;
    cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
    std::vector<TruthBox> truths;
    const fs::path label_path = LabelPathOf(path);
    if (fs::exists(label_path)) {  // no label file: an image without objects (ultralytics)
      Result<std::vector<YoloLabel>> labels =
          ReadYoloLabels(label_path, static_cast<int>(dataset.names.size()));
      if (!labels.ok()) return labels.status();
      for (const YoloLabel& label : *labels) {
        truths.push_back({label.class_id, label.PixelBox(rgb.cols, rgb.rows)});
      }
    }
    const auto start = std::chrono::steady_clock::now();
    Result<std::vector<Detection>> detections = detector.Detect(rgb);
    const auto stop = std::chrono::steady_clock::now();
    if (!detections.ok()) return detections.status();
    times_ms.push_back(std::chrono::duration<double, std::milli>(stop - start).count());
    evaluator.AddImage(*detections, truths);
    result.confusion.AddImage(*detections, truths);
    result.truths += static_cast<int>(truths.size());
    ++result.images;
    if (progress) progress(result.images, static_cast<int>(images->size()));
  }
  result.accuracy = evaluator.Evaluate();
  result.mean_ms =
      std::accumulate(times_ms.begin(), times_ms.end(), 0.0) / static_cast<double>(times_ms.size());
  std::nth_element(times_ms.begin(), times_ms.begin() + times_ms.size() / 2, times_ms.end());
  result.median_ms = times_ms[times_ms.size() / 2];
  return result;
}

}  // namespace semchain::detection
