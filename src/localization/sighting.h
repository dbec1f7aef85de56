#pragma once

#include "core/pose2.h"

namespace semchain::localization {

// A pose as it held at an odometry reading. Between two readings the robot moved by the odometry
// increment, so the pose at a later reading is this one composed with that increment (At).
struct Sighting {
  Pose2 pose;
  Pose2 odometry;

  Pose2 At(const Pose2& later) const { return pose * odometry.Between(later); }
};

}  // namespace semchain::localization
