#include "detection/detection_metrics.h"

#include <algorithm>
#include <numeric>

namespace semchain::detection {

double BoxIou(const std::array<double, 4>& a, const std::array<double, 4>& b) {
  const double w = std::min(a[2], b[2]) - std::max(a[0], b[0]);
  const double h = std::min(a[3], b[3]) - std::max(a[1], b[1]);
  if (w <= 0.0 || h <= 0.0) return 0.0;
  const double inter = w * h;
  const double area_a = (a[2] - a[0]) * (a[3] - a[1]), area_b = (b[2] - b[0]) * (b[3] - b[1]);
  const double union_area = area_a + area_b - inter;
  return union_area > 0.0 ? inter / union_area : 0.0;
}

double AveragePrecision(const std::vector<double>& recall, const std::vector<double>& precision) {
  if (recall.empty()) return 0.0;
  // The precision envelope: at each recall, the best precision at that recall or beyond.
  std::vector<double> envelope(precision);
  for (std::size_t i = envelope.size() - 1; i > 0; --i) {
    envelope[i - 1] = std::max(envelope[i - 1], envelope[i]);
  }
  double sum = 0.0;
  std::size_t k = 0;
  for (int i = 0; i <= 100; ++i) {
    const double r = i / 100.0;
    while (k < recall.size() && recall[k] < r - 1e-12) ++k;
    if (k == recall.size()) break;  // recall never reaches r: precision 0 from here on
    sum += envelope[k];
  }
  return sum / 101.0;
}

DetectionEvaluator::DetectionEvaluator(int class_count)
    : class_count_(class_count), scored_(class_count), truths_(class_count, 0) {}

void DetectionEvaluator::AddImage(const std::vector<Detection>& detections,
                                  const std::vector<TruthBox>& truths) {
  for (const TruthBox& truth : truths) {
    if (truth.class_id >= 0 && truth.class_id < class_count_) ++truths_[truth.class_id];
  }
  std::vector<std::size_t> order(detections.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return detections[a].score > detections[b].score;
  });
  // taken[t][j]: truth j already matched at threshold t.
  std::vector<std::array<bool, kThresholds>> taken(truths.size());
  for (auto& row : taken) row.fill(false);
  for (const std::size_t i : order) {
    const Detection& detection = detections[i];
    if (detection.class_id < 0 || detection.class_id >= class_count_) continue;
    const std::array<double, 4> box = BoxOf(detection);
    Scored scored{detection.score, {}};
    for (int t = 0; t < kThresholds; ++t) {
      const double threshold = 0.5 + 0.05 * t;
      int best = -1;
      double best_iou = 0.0;
      for (std::size_t j = 0; j < truths.size(); ++j) {
        if (truths[j].class_id != detection.class_id || taken[j][t]) continue;
        const double iou = BoxIou(box, truths[j].box);
        if (iou >= threshold - 1e-12 && iou > best_iou) best = static_cast<int>(j), best_iou = iou;
      }
      scored.true_positive[t] = best >= 0;
      if (best >= 0) taken[best][t] = true;
    }
    scored_[detection.class_id].push_back(scored);
  }
}

DetectionAccuracy DetectionEvaluator::Evaluate() const {
  DetectionAccuracy accuracy;
  accuracy.classes.resize(class_count_);
  int with_truth = 0;
  // Precision and recall per class on a grid of confidences, for the best mean F1.
  constexpr int kConfidences = 1000;
  std::vector<double> mean_precision(kConfidences, 0.0), mean_recall(kConfidences, 0.0);
  for (int c = 0; c < class_count_; ++c) {
    ClassAccuracy& result = accuracy.classes[c];
    result.truths = truths_[c];
    if (truths_[c] == 0) continue;
    ++with_truth;
    std::vector<Scored> scored = scored_[c];
    std::stable_sort(scored.begin(), scored.end(),
                     [](const Scored& a, const Scored& b) { return a.score > b.score; });
    for (int t = 0; t < kThresholds; ++t) {
      std::vector<double> recall, precision;
      int tp = 0;
      for (std::size_t i = 0; i < scored.size(); ++i) {
        tp += scored[i].true_positive[t] ? 1 : 0;
        recall.push_back(static_cast<double>(tp) / truths_[c]);
        precision.push_back(static_cast<double>(tp) / static_cast<double>(i + 1));
      }
      const double ap = AveragePrecision(recall, precision);
      if (t == 0) result.ap50 = ap;
      result.ap50_95 += ap / kThresholds;
    }
    for (int k = 0; k < kConfidences; ++k) {
      const double confidence = static_cast<double>(k) / kConfidences;
      int tp = 0, predicted = 0;
      for (const Scored& s : scored) {
        if (s.score < confidence) break;
        ++predicted;
        tp += s.true_positive[0] ? 1 : 0;
      }
      mean_precision[k] += predicted > 0 ? static_cast<double>(tp) / predicted : 1.0;
      mean_recall[k] += static_cast<double>(tp) / truths_[c];
    }
  }
  if (with_truth == 0) return accuracy;
  double best_f1 = -1.0;
  for (int k = 0; k < kConfidences; ++k) {
    const double p = mean_precision[k] / with_truth, r = mean_recall[k] / with_truth;
    const double f1 = p + r > 0.0 ? 2.0 * p * r / (p + r) : 0.0;
    if (f1 > best_f1) {
      best_f1 = f1;
      accuracy.precision = p, accuracy.recall = r;
      accuracy.confidence = static_cast<double>(k) / kConfidences;
    }
  }
  for (const ClassAccuracy& c : accuracy.classes) {
    if (c.truths == 0) continue;
    accuracy.map50 += c.ap50 / with_truth;
    accuracy.map50_95 += c.ap50_95 / with_truth;
  }
  return accuracy;
}

}  // namespace semchain::detection
