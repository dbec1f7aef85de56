#include "detection/class_nms.h"

#include <algorithm>
#include <map>
#include <opencv2/dnn.hpp>

namespace semchain::detection {

std::vector<int> ClassWiseNms(const std::vector<Candidate>& candidates, double iou_threshold,
                              int max_count) {
  // OpenCV 4.6 has no NMSBoxesBatched: run NMSBoxes on each class's candidates.
  std::map<int, std::vector<int>> by_class;
  for (int i = 0; i < int(candidates.size()); ++i) by_class[candidates[i].class_id].push_back(i);
  std::vector<int> kept;
  for (const auto& [class_id, members] : by_class) {
    std::vector<cv::Rect2d> boxes;
    std::vector<float> scores;
    for (int i : members) {
      boxes.push_back(candidates[i].box);
      scores.push_back(candidates[i].score);
    }
    std::vector<int> survivors;
    // Every candidate already passed the confidence threshold (> 0): keep all scores here.
    cv::dnn::NMSBoxes(boxes, scores, 0.0f, float(iou_threshold), survivors);
    for (int s : survivors) kept.push_back(members[s]);
  }
  std::stable_sort(kept.begin(), kept.end(), [&candidates](int a, int b) {
    return candidates[a].score > candidates[b].score ||
           (candidates[a].score == candidates[b].score && a < b);
  });
  if (max_count >= 0 && int(kept.size()) > max_count) kept.resize(max_count);
  return kept;
}

}  // namespace semchain::detection
