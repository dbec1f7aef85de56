#pragma once

#include <filesystem>
#include <vector>

#include "core/pose2.h"
#include "core/status.h"

namespace semchain {

struct StampedPose {
  double timestamp = 0.0;
  Pose2 pose;
};

// Trajectory files: one "timestamp x y theta" line per pose; '#' starts a comment line.
Result<std::vector<StampedPose>> ReadTrajectory(const std::filesystem::path& path);
Status WriteTrajectory(const std::filesystem::path& path, const std::vector<StampedPose>& poses);

}  // namespace semchain
