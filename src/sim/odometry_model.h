#pragma once

#include <array>

#include "core/pose2.h"
#include "core/rng.h"

// Simulated wheel odometry with the odometry motion model of Thrun, Burgard and Fox,
// Probabilistic Robotics (2005), table 5.6 (sample_motion_model_odometry): a motion is a
// rotation δrot1 towards the direction of travel, a translation δtrans and a rotation δrot2;
// each is perturbed by zero-mean Gaussian noise whose variance grows with the motion:
//   var(δrot1) = α1 δrot1² + α2 δtrans²
//   var(δtrans) = α3 δtrans² + α4 (δrot1² + δrot2²)
//   var(δrot2) = α1 δrot2² + α2 δtrans²
// The book samples a true pose from an odometry reading; the simulator runs the same model the
// other way round: the true motion is perturbed and added to the odometry pose.
namespace semchain::sim {

// Systematic odometry error: fractions by which the odometry over-reads translations and
// rotations (a wheel radius 1 % too large gives distance = 0.01).
struct OdometryScaleError {
  double distance = 0.0;
  double turn = 0.0;
};

struct OdometryIncrement {
  double rot1 = 0.0;   // radians
  double trans = 0.0;  // metres
  double rot2 = 0.0;   // radians
};

// Decomposes the motion 'from' → 'to' (table 5.6, lines 2–4). A translation shorter than
// 'min_translation' is treated as a rotation in place (δrot1 = 0), where atan2 is meaningless.
OdometryIncrement ComputeIncrement(const Pose2& from, const Pose2& to,
                                   double min_translation = 1e-6);

// The pose reached from 'pose' by 'increment' (table 5.6, lines 8–10).
Pose2 ApplyIncrement(const Pose2& pose, const OdometryIncrement& increment);

// 'increment' perturbed by the model's noise (table 5.6, lines 5–7).
OdometryIncrement SampleIncrement(const OdometryIncrement& increment,
                                  const std::array<double, 4>& alphas, Rng& rng);

// Accumulates noisy odometry along a true trajectory. The odometry starts at the true start
// pose, so a map built from it is in world coordinates (DESIGN.md §3.1).
class OdometrySimulator {
 public:
  OdometrySimulator(const std::array<double, 4>& alphas, const Pose2& true_start,
                    const OdometryScaleError& scale_error = {});

  // Moves the robot truly to 'truth' and returns the odometry pose after the move.
  const Pose2& Step(const Pose2& truth, Rng& rng);
  const Pose2& pose() const { return odometry_; }

 private:
  std::array<double, 4> alphas_;
  OdometryScaleError scale_error_;
  Pose2 truth_;
  Pose2 odometry_;
};

}  // namespace semchain::sim
