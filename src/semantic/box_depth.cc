#include "semantic/box_depth.h"

#include <algorithm>
#include <cmath>

namespace semchain::semantic {

cv::Mat DepthFromBoxes(const std::vector<Detection>& detections, const PinholeCamera& camera) {
  cv::Mat depth(camera.height, camera.width, CV_32FC1, cv::Scalar(0.0f));
  std::vector<const Detection*> far_first;
  for (const Detection& d : detections) {
    if (d.depth_m > 0.0 && std::isfinite(d.depth_m)) far_first.push_back(&d);
  }
  std::stable_sort(far_first.begin(), far_first.end(),
                   [](const Detection* a, const Detection* b) { return a->depth_m > b->depth_m; });
  for (const Detection* d : far_first) {
    // Box edges are pixel boundaries: pixel u covers [u - 0.5, u + 0.5).
    const int u0 = std::max(0, static_cast<int>(std::ceil(d->box[0] - 0.5)));
    const int u1 = std::min(camera.width - 1, static_cast<int>(std::floor(d->box[2] - 0.5)));
    const int v0 = std::max(0, static_cast<int>(std::ceil(d->box[1] - 0.5)));
    const int v1 = std::min(camera.height - 1, static_cast<int>(std::floor(d->box[3] - 0.5)));
    if (u1 < u0 || v1 < v0) continue;
    depth(cv::Range(v0, v1 + 1), cv::Range(u0, u1 + 1)).setTo(static_cast<float>(d->depth_m));
  }
  return depth;
}

}  // namespace semchain::semantic
