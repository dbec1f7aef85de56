#include "eval/map_frame.h"

#include <limits>
#include <optional>

#include "io/trajectory_lookup.h"

namespace semchain::eval {

Result<MapFrame> MapFrame::FromTrajectories(const std::vector<StampedPose>& estimate,
                                            const std::vector<StampedPose>& truth,
                                            double timestamp_tolerance_s) {
  const TrajectoryLookup lookup(truth);
  MapFrame frame;
  for (const StampedPose& pose : estimate) {
    const std::optional<Pose2> true_pose = lookup.Nearest(pose.timestamp, timestamp_tolerance_s);
    if (!true_pose) continue;
    frame.truth_.push_back(*true_pose);
    frame.map_from_world_.push_back(pose.pose * true_pose->Inverse());
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
