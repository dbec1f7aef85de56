#pragma once

#include <Eigen/Core>
#include <string>

#include "core/pose2.h"
#include "core/rng.h"

// The odometry motion model p(x_t | x_{t-1}, u_{t-1}) of the RBPF: the odometry increment u
// (the motion between two processed scans in the frame of the first) with Gaussian noise whose
// standard deviations grow with the distance travelled and the angle turned (the noise model
// of GMapping's srr, srt, str, stt; Probabilistic Robotics §5.4 in spirit).
namespace semchain::mapping {

// The defaults suit the scan-matched odometry the filter sees by default (LaserOdometryOptions);
// for wheel odometry GMapping's srr 0.1, str 0.1... (config/slam-gmapping.yaml).
struct MotionModelOptions {
  double translation_per_meter = 0.05;   // σ_xy grows by this many m per m driven (srr)
  double translation_per_radian = 0.05;  // ... and by this many m per rad turned (str)
  double rotation_per_meter = 0.02;      // σ_θ grows by this many rad per m driven (srt)
  double rotation_per_radian = 0.05;     // ... and by this many rad per rad turned (stt)
  // Floors that keep the density proper when the robot barely moved.
  double min_translation_sigma_meters = 0.002;
  double min_rotation_sigma_radians = 0.001;

  bool Validate(std::string* error) const;
};

class MotionModel {
 public:
  explicit MotionModel(const MotionModelOptions& options);

  // Standard deviations (x, y, θ) of the noise on 'increment', in the robot frame.
  Eigen::Vector3d Sigmas(const Pose2& increment) const;
  // The predicted pose without noise: previous ⊕ increment.
  static Pose2 Predict(const Pose2& previous, const Pose2& increment) {
    return previous * increment;
  }
  // Draws x_t ~ p(x_t | previous, increment).
  Pose2 Sample(const Pose2& previous, const Pose2& increment, Rng& rng) const;
  // log p(x | previous, increment) up to a constant: the Gaussian of Sigmas() evaluated on the
  // difference between 'x' and the prediction, in the prediction's frame.
  double LogDensity(const Pose2& x, const Pose2& previous, const Pose2& increment) const;

  const MotionModelOptions& options() const { return options_; }

 private:
  MotionModelOptions options_;
};

}  // namespace semchain::mapping
