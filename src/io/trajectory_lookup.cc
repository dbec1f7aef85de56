#include "io/trajectory_lookup.h"

#include <algorithm>
#include <cmath>

namespace semchain {

TrajectoryLookup::TrajectoryLookup(std::vector<StampedPose> poses) : poses_(std::move(poses)) {
  std::stable_sort(poses_.begin(), poses_.end(), [](const StampedPose& a, const StampedPose& b) {
    return a.timestamp < b.timestamp;
  });
}

std::size_t TrajectoryLookup::LowerBound(double t) const {
  const auto it =
      std::lower_bound(poses_.begin(), poses_.end(), t,
                       [](const StampedPose& p, double time) { return p.timestamp < time; });
  return static_cast<std::size_t>(it - poses_.begin());
}

std::optional<Pose2> TrajectoryLookup::Nearest(double t, double tolerance) const {
  const std::size_t upper = LowerBound(t);
  std::optional<std::size_t> best;
  double best_gap = tolerance;
  // Only the poses just before and just after 't' can be the nearest.
  for (const std::size_t i : {upper - 1, upper}) {
    if (i >= poses_.size()) continue;  // also catches upper - 1 wrapping below 0
    const double gap = std::abs(poses_[i].timestamp - t);
    if (gap <= best_gap) {
      best_gap = gap;
      best = i;
    }
  }
  if (!best) return std::nullopt;
  return poses_[*best].pose;
}

std::optional<Pose2> TrajectoryLookup::At(double t, double tolerance, double max_gap) const {
  if (std::optional<Pose2> nearest = Nearest(t, tolerance)) return nearest;
  const std::size_t upper = LowerBound(t);
  if (upper == 0 || upper >= poses_.size()) return std::nullopt;
  const StampedPose& a = poses_[upper - 1];
  const StampedPose& b = poses_[upper];
  const double gap = b.timestamp - a.timestamp;
  if (gap > max_gap || gap <= 0.0) return std::nullopt;
  return Interpolate(a.pose, b.pose, (t - a.timestamp) / gap);
}

}  // namespace semchain
