#pragma once

#include <Eigen/Core>
#include <string>

#include "core/pose2.h"
#include "core/rng.h"

// The odometry motion model p(x_t | x_{t-1}, u_{t-1}) of the RBPF: the odometry increment u
// (the motion between two processed scans in the frame of the first) with Gaussian noise whose
// standard deviations grow with the distance travelled and the angle turned (the noise model
// of GMapping's srr, srt, str, stt; Probabilistic Robotics §5.4 in spirit).
//
// GMapping draws that noise at every odometry reading, not once per processed scan: the errors of
// the ~10–20 readings between two processed scans are independent, so their spread grows with the
// square root of the readings' count, not linearly with the whole increment. One draw over the
// whole increment is about four times wider on wheel odometry (aces: σ_θ 17° instead of 4° for
// a 1 m step). With per_reading_noise the filter feeds every reading's step to a MotionStep,
// whose covariance is propagated as the readings compose. It did not reduce the ACES failures
// and broke FR079 maps that were fine (docs/experiments.md), so it is
// off by default.
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
  // true: the noise accumulates reading by reading, as GMapping draws it; false: one draw over
  // the increment between two processed scans.
  bool per_reading_noise = false;

  bool Validate(std::string* error) const;
};

// An odometry increment with the covariance of its noise (x, y, θ in the frame of the
// increment's end: the noisy pose is previous ⊕ increment ⊕ noise).
struct MotionStep {
  Pose2 increment;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

class MotionModel {
 public:
  explicit MotionModel(const MotionModelOptions& options);

  // Standard deviations (x, y, θ) of one draw of noise on 'increment', in the robot frame.
  Eigen::Vector3d Sigmas(const Pose2& increment) const;
  // The increment with one draw's covariance (the floors applied).
  MotionStep Step(const Pose2& increment) const;
  // Appends one reading's 'step' to 'total': total ⊕ step, the covariance propagated to the new
  // end frame to first order (the heading noise so far moves the step's translation) plus the
  // step's own noise without floors, so that standing still adds nothing.
  void Accumulate(const Pose2& step, MotionStep* total) const;
  // Standard deviations of 'step' (its covariance's diagonal, floors applied).
  Eigen::Vector3d Sigmas(const MotionStep& step) const;
  // The predicted pose without noise: previous ⊕ increment.
  static Pose2 Predict(const Pose2& previous, const Pose2& increment) {
    return previous * increment;
  }
  // Draws x_t ~ p(x_t | previous, step).
  Pose2 Sample(const Pose2& previous, const MotionStep& step, Rng& rng) const;
  Pose2 Sample(const Pose2& previous, const Pose2& increment, Rng& rng) const {
    return Sample(previous, Step(increment), rng);
  }
  // log p(x | previous, step) up to a constant: the Gaussian of the step's covariance evaluated
  // on the difference between 'x' and the prediction, in the prediction's frame.
  double LogDensity(const Pose2& x, const Pose2& previous, const MotionStep& step) const;
  double LogDensity(const Pose2& x, const Pose2& previous, const Pose2& increment) const {
    return LogDensity(x, previous, Step(increment));
  }

  const MotionModelOptions& options() const { return options_; }

 private:
  // The covariance with its diagonal raised to the floors.
  Eigen::Matrix3d Floored(const Eigen::Matrix3d& covariance) const;
  // One draw's σ_xy and σ_θ on 'increment', without floors.
  Eigen::Vector2d LinearSigmas(const Pose2& increment) const;
  // One draw's covariance on 'increment', without floors.
  Eigen::Matrix3d RawCovariance(const Pose2& increment) const;

  MotionModelOptions options_;
};

}  // namespace semchain::mapping
