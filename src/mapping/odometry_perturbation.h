#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "io/carmen.h"
#include "io/trajectory_io.h"

// Synthetic odometry for SLAM tests on corrected logs (shared/data/README.md): the laser poses of
// a corrected log are the truth; the odometry is rebuilt from their increments with seeded
// noise and a systematic error, so that the SLAM result can be scored by ATE against the truth.
// Every number obtained this way is labelled "synthetic-odometry".
namespace semchain::mapping {

struct OdometryPerturbationOptions {
  std::uint64_t seed = 1;
  // Random error per increment: σ_xy = a·|d| + b·|Δθ|, σ_θ = c·|d| + e·|Δθ|.
  double translation_per_meter = 0.05;
  double translation_per_radian = 0.01;
  double rotation_per_meter = 0.02;
  double rotation_per_radian = 0.05;
  // Systematic error: distances read this much too long, turns this much too short (relative).
  double distance_scale_error = 0.02;
  double turn_scale_error = -0.02;

  bool Validate(std::string* error) const;
};

// The truth (robot pose of every laser record, in log order) and a copy of 'log' whose laser
// records carry the perturbed odometry (laser poses moved with it, the laser offset kept). The
// perturbed odometry starts at the true first pose.
struct PerturbedLog {
  carmen::Log log;
  std::vector<StampedPose> truth;
};
PerturbedLog PerturbOdometry(const carmen::Log& log, const OdometryPerturbationOptions& options);

}  // namespace semchain::mapping
