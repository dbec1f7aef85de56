#include "eval/map_frame.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace semchain::eval {

Result<MapFrame> MapFrame::FromTrajectories(const std::vector<StampedPose>& estimate,
                                            const std::vector<StampedPose>& truth,
                                            double timestamp_tolerance_s) {
  std::vector<StampedPose> by_time = truth;
  std::sort(by_time.begin(), by_time.end(),
            [](const StampedPose& a, const StampedPose& b) { return a.timestamp < b.timestamp; });
  MapFrame frame;
  for (const StampedPose& pose : estimate) {
    const auto next =
        std::lower_bound(by_time.begin(), by_time.end(), pose.timestamp,
                         [](const StampedPose& p, double t) { return p.timestamp < t; });
    const StampedPose* nearest = nullptr;
    double gap = std::numeric_limits<double>::infinity();
    if (next != by_time.end()) {
      nearest = &*next;
      gap = next->timestamp - pose.timestamp;
    }
    if (next != by_time.begin() && pose.timestamp - std::prev(next)->timestamp < gap) {
      nearest = &*std::prev(next);
      gap = pose.timestamp - nearest->timestamp;
    }
    if (nearest == nullptr || gap > timestamp_tolerance_s) continue;
    frame.truth_.push_back(nearest->pose);
    frame.map_from_world_.push_back(pose.pose * nearest->pose.Inverse());
  }
  if (frame.truth_.empty()) {
    return Status::Error("map frame: no estimated pose of the mapping run has a truth pose");
  }
  return frame;
}

Pose2 MapFrame::FromWorld(const Pose2& world) const {
  std::size_t nearest = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < truth_.size(); ++i) {
    const double d = (truth_[i].translation() - world.translation()).squaredNorm();
    if (d < best) {
      best = d;
      nearest = i;
    }
  }
  return map_from_world_[nearest] * world;
}

}  // namespace semchain::eval
