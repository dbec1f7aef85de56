#include "detection/box_depth.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/check.h"

namespace semchain::detection {
namespace {

// The pixels whose centres u + 0.5 lie in [low, high), widened to the pixel under the middle
// when none does, clamped to [0, size).
cv::Range PixelsWithin(double low, double high, int size) {
  int first = int(std::ceil(low - 0.5)), last = int(std::ceil(high - 0.5));  // [first, last)
  if (last <= first) {
    first = int(std::floor(0.5 * (low + high)));
    last = first + 1;
  }
  return cv::Range(std::clamp(first, 0, size), std::clamp(last, 0, size));
}

double UpperMedian(std::vector<float>::iterator begin, std::vector<float>::iterator end) {
  const auto middle = begin + (end - begin) / 2;
  std::nth_element(begin, middle, end);
  return *middle;
}

struct BoxPixels {
  std::vector<float> depths;  // valid readings, floor left out
  double pixels = 0.0;        // in the window
  double valid = 0.0;         // with a reading, floor included
};

BoxPixels CollectDepths(const cv::Mat& depth_m, const cv::Range& rows, const cv::Range& cols,
                        const MountedCamera* camera, double floor_height) {
  BoxPixels collected;
  collected.pixels = double(cols.size()) * rows.size();
  for (int v = rows.start; v < rows.end; ++v) {
    const float* row = depth_m.ptr<float>(v);
    for (int u = cols.start; u < cols.end; ++u) {
      if (!(std::isfinite(row[u]) && row[u] > 0.0f)) continue;
      collected.valid += 1.0;
      if (camera != nullptr) {
        const Eigen::Vector3d in_robot =
            camera->robot_from_camera * camera->intrinsics.Backproject(u, v, row[u]);
        if (in_robot.z() < floor_height) continue;
      }
      collected.depths.push_back(row[u]);
    }
  }
  return collected;
}

// The median of the nearest run of contiguous depths holding 'min_fraction' of them; of the
// largest run when none does.
double NearestSurface(std::vector<float> depths, double gap, double min_fraction) {
  std::sort(depths.begin(), depths.end());
  const double needed = min_fraction * double(depths.size());
  auto largest_begin = depths.begin(), largest_end = depths.begin();
  auto begin = depths.begin();
  for (auto it = depths.begin() + 1;; ++it) {
    if (it != depths.end() && *it - *(it - 1) <= gap) continue;
    if (double(it - begin) >= needed) return UpperMedian(begin, it);
    if (it - begin > largest_end - largest_begin) largest_begin = begin, largest_end = it;
    if (it == depths.end()) break;
    begin = it;
  }
  return UpperMedian(largest_begin, largest_end);
}

}  // namespace

bool BoxDepthOptions::Validate(std::string* error) const {
  if (!(core_fraction > 0.0 && core_fraction <= 1.0)) {
    *error = "core_fraction must be in (0, 1]";
    return false;
  }
  if (!(trim_fraction >= 0.0 && trim_fraction < 0.5)) {
    *error = "trim_fraction must be in [0, 0.5)";
    return false;
  }
  if (!(surface_gap > 0.0)) {
    *error = "surface_gap must be > 0";
    return false;
  }
  if (!(min_surface_fraction >= 0.0 && min_surface_fraction <= 1.0)) {
    *error = "min_surface_fraction must be in [0, 1]";
    return false;
  }
  if (!(min_valid_fraction >= 0.0 && min_valid_fraction <= 1.0)) {
    *error = "min_valid_fraction must be in [0, 1]";
    return false;
  }
  if (!std::isfinite(floor_height)) {
    *error = "floor_height must be finite";
    return false;
  }
  return true;
}

std::optional<double> BoxDepth(const cv::Mat& depth_m, const double box[4],
                               const MountedCamera* camera, const BoxDepthOptions& options) {
  SEMCHAIN_CHECK(depth_m.type() == CV_32FC1);
  const bool core = options.method == BoxDepthMethod::kCoreMedian;
  const double margin = core ? 0.5 * (1.0 - options.core_fraction) : options.trim_fraction;
  const double w = box[2] - box[0], h = box[3] - box[1];
  const cv::Range cols = PixelsWithin(box[0] + margin * w, box[2] - margin * w, depth_m.cols);
  const cv::Range rows = PixelsWithin(box[1] + margin * h, box[3] - margin * h, depth_m.rows);
  if (cols.empty() || rows.empty()) return std::nullopt;
  BoxPixels collected =
      CollectDepths(depth_m, rows, cols, core ? nullptr : camera, options.floor_height);
  if (collected.depths.empty() || collected.valid < options.min_valid_fraction * collected.pixels) {
    return std::nullopt;
  }
  if (core) return UpperMedian(collected.depths.begin(), collected.depths.end());
  return NearestSurface(std::move(collected.depths), options.surface_gap,
                        options.min_surface_fraction);
}

}  // namespace semchain::detection
