#include "detection/confusion_matrix.h"

#include <algorithm>
#include <tuple>

namespace semchain::detection {

ConfusionMatrix::ConfusionMatrix(int class_count, const ConfusionOptions& options)
    : class_count_(class_count),
      options_(options),
      counts_(class_count + 1, std::vector<int>(class_count + 1, 0)) {}

void ConfusionMatrix::AddImage(const std::vector<Detection>& detections,
                               const std::vector<TruthBox>& truths) {
  const auto known = [this](int id) { return id >= 0 && id < class_count_; };
  const auto counted = [&](const Detection& detection) {
    return detection.score >= options_.min_score && known(detection.class_id);
  };
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;  // IoU, detection, truth
  for (std::size_t d = 0; d < detections.size(); ++d) {
    if (!counted(detections[d])) continue;
    const std::array<double, 4> box = BoxOf(detections[d]);
    for (std::size_t t = 0; t < truths.size(); ++t) {
      if (!known(truths[t].class_id)) continue;
      const double iou = BoxIou(box, truths[t].box);
      if (iou >= options_.min_iou) pairs.emplace_back(iou, d, t);
    }
  }
  // Largest overlap first; ties in input order, so that a result does not depend on the sort.
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const auto& a, const auto& b) { return std::get<0>(a) > std::get<0>(b); });
  std::vector<bool> detection_paired(detections.size(), false), truth_paired(truths.size(), false);
  for (const auto& [iou, d, t] : pairs) {
    if (detection_paired[d] || truth_paired[t]) continue;
    detection_paired[d] = truth_paired[t] = true;
    ++counts_[truths[t].class_id][detections[d].class_id];
  }
  for (std::size_t t = 0; t < truths.size(); ++t) {
    if (known(truths[t].class_id) && !truth_paired[t]) ++counts_[truths[t].class_id][class_count_];
  }
  for (std::size_t d = 0; d < detections.size(); ++d) {
    if (!detection_paired[d] && counted(detections[d]))
      ++counts_[class_count_][detections[d].class_id];
  }
}

}  // namespace semchain::detection
