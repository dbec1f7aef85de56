#include "detection/box_depth.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/check.h"

namespace semchain::detection {
namespace {

// The pixels whose centres u + 0.5 lie in [low, high), widened to the pixel under the middle
// when none does, clamped to [0, size).
cv::Range CorePixels(double low, double high, int size) {
  int first = int(std::ceil(low - 0.5)), last = int(std::ceil(high - 0.5));  // [first, last)
  if (last <= first) {
    first = int(std::floor(0.5 * (low + high)));
    last = first + 1;
  }
  return cv::Range(std::clamp(first, 0, size), std::clamp(last, 0, size));
}

}  // namespace

bool BoxDepthOptions::Validate(std::string* error) const {
  if (!(core_fraction > 0.0 && core_fraction <= 1.0)) {
    *error = "core_fraction must be in (0, 1]";
    return false;
  }
  if (!(min_valid_fraction >= 0.0 && min_valid_fraction <= 1.0)) {
    *error = "min_valid_fraction must be in [0, 1]";
    return false;
  }
  return true;
}

std::optional<double> BoxDepth(const cv::Mat& depth_m, const double box[4],
                               const BoxDepthOptions& options) {
  SEMCHAIN_CHECK(depth_m.type() == CV_32FC1);
  const double margin = 0.5 * (1.0 - options.core_fraction);
  const double w = box[2] - box[0], h = box[3] - box[1];
  const cv::Range cols = CorePixels(box[0] + margin * w, box[2] - margin * w, depth_m.cols);
  const cv::Range rows = CorePixels(box[1] + margin * h, box[3] - margin * h, depth_m.rows);
  if (cols.empty() || rows.empty()) return std::nullopt;
  std::vector<float> valid;
  for (int v = rows.start; v < rows.end; ++v) {
    const float* row = depth_m.ptr<float>(v);
    for (int u = cols.start; u < cols.end; ++u) {
      if (std::isfinite(row[u]) && row[u] > 0.0f) valid.push_back(row[u]);
    }
  }
  const double pixels = double(cols.size()) * rows.size();
  if (valid.empty() || double(valid.size()) < options.min_valid_fraction * pixels) {
    return std::nullopt;
  }
  const auto middle = valid.begin() + std::ptrdiff_t(valid.size() / 2);
  std::nth_element(valid.begin(), middle, valid.end());
  return *middle;
}

}  // namespace semchain::detection
