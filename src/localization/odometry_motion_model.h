#pragma once

#include "core/pose2.h"
#include "core/rng.h"

// The odometry motion model of Probabilistic Robotics, Table 5.6 (sample_motion_model_odometry),
// as nav2's DifferentialMotionModel applies it: the odometry motion between two filter updates
// is split into a first rotation, a translation and a second rotation, each perturbed by a
// zero-mean Gaussian whose variance grows with the motion (alpha1–alpha4).
namespace semchain::localization {

struct OdometryMotionNoise {
  double alpha1 = 0.2;  // rotation noise from rotation
  double alpha2 = 0.2;  // rotation noise from translation
  double alpha3 = 0.2;  // translation noise from translation
  double alpha4 = 0.2;  // translation noise from rotation
};

// u = (δrot1, δtrans, δrot2) of the odometry motion 'from' → 'to'.
struct OdometryMotion {
  double rot1 = 0.0;
  double trans = 0.0;
  double rot2 = 0.0;
  // The rotations that drive the noise: a robot driving backwards turns by about π in the
  // decomposition, which must not count as a large rotation (nav2: the smaller of |δ| and
  // |δ − π|).
  double rot1_noise = 0.0;
  double rot2_noise = 0.0;

  // Decomposes the odometry motion. Below 1 cm of translation δrot1 is 0, as in nav2, because
  // the direction of a tiny translation is noise.
  static OdometryMotion Between(const Pose2& from, const Pose2& to);
};

class OdometryMotionModel {
 public:
  explicit OdometryMotionModel(const OdometryMotionNoise& noise) : noise_(noise) {}

  // The standard deviations of the three perturbations, computed once per motion.
  struct Sigmas {
    double rot1 = 0.0;
    double trans = 0.0;
    double rot2 = 0.0;
  };
  Sigmas SigmasOf(const OdometryMotion& u) const {
    return {Rot1Sigma(u), TransSigma(u), Rot2Sigma(u)};
  }

  // Draws x_t ~ p(x_t | u, x_{t−1} = 'pose').
  Pose2 Sample(const Pose2& pose, const OdometryMotion& u, Rng& rng) const {
    return Sample(pose, u, SigmasOf(u), rng);
  }
  // The same with the sigmas of 'u' given ('sigmas' = SigmasOf(u)): a filter moves every particle
  // by the same 'u' and need not recompute three square roots per particle.
  static Pose2 Sample(const Pose2& pose, const OdometryMotion& u, const Sigmas& sigmas, Rng& rng);

  // The standard deviations of the three perturbations for 'u': (δrot1, δtrans, δrot2).
  double Rot1Sigma(const OdometryMotion& u) const;
  double TransSigma(const OdometryMotion& u) const;
  double Rot2Sigma(const OdometryMotion& u) const;

 private:
  OdometryMotionNoise noise_;
};

}  // namespace semchain::localization
