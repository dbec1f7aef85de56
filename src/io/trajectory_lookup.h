#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "core/pose2.h"
#include "io/trajectory_io.h"

namespace semchain {

// Looks up poses of a trajectory by timestamp.
class TrajectoryLookup {
 public:
  // 'poses' in any order; they are sorted by timestamp here.
  explicit TrajectoryLookup(std::vector<StampedPose> poses);

  // The pose whose timestamp is nearest to 't', when it is within 'tolerance' seconds.
  std::optional<Pose2> Nearest(double t, double tolerance) const;

  // The pose at 't': the nearest one within 'tolerance', otherwise interpolated between the two
  // poses around 't' (Pose2 Interpolate: linear, heading on the shorter arc) when they are at
  // most 'max_gap' seconds apart. Nothing when 't' is outside the trajectory or in a larger gap.
  std::optional<Pose2> At(double t, double tolerance, double max_gap) const;

  std::size_t size() const { return poses_.size(); }

 private:
  // Index of the first pose with timestamp >= t.
  std::size_t LowerBound(double t) const;

  std::vector<StampedPose> poses_;
};

}  // namespace semchain
