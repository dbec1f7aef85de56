#pragma once

#include <vector>

#include "core/pose2.h"
#include "core/status.h"
#include "io/trajectory_io.h"

// Where the world's truth lies in the frame of a map built by SLAM. A SLAM map is drawn from the
// estimated trajectory, so each place in it is off the world by that trajectory's error there
// (a slow bend of a corridor, a few centimetres to a decimetre). A relocalizer that finds the
// robot exactly where the map shows it is off the world's truth by as much; measured in the
// map's frame, its own error is separated from the map's.
namespace semchain::eval {

class MapFrame {
 public:
  // Pairs the mapping run's estimated poses with its truth by timestamp (within
  // 'timestamp_tolerance_s'); fails when none pair.
  static Result<MapFrame> FromTrajectories(const std::vector<StampedPose>& estimate,
                                           const std::vector<StampedPose>& truth,
                                           double timestamp_tolerance_s = 1e-3);

  // 'world' moved into the map's frame by the correction (estimate ⊕ truth⁻¹) at the mapping
  // run's truth pose nearest to it.
  Pose2 FromWorld(const Pose2& world) const;

 private:
  std::vector<Pose2> truth_;
  std::vector<Pose2> map_from_world_;
};

}  // namespace semchain::eval
