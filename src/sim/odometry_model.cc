#include "sim/odometry_model.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "core/angles.h"

namespace semchain::sim {
namespace {

// A zero-mean Gaussian sample of the given variance (the book's sample(b²)). It draws even for
// a zero variance, so that the number of draws never depends on the motion.
double SampleWithVariance(double variance, Rng& rng) {
  return std::sqrt(std::max(variance, 0.0)) * std::normal_distribution<double>(0.0, 1.0)(rng);
}

}  // namespace

OdometryIncrement ComputeIncrement(const Pose2& from, const Pose2& to, double min_translation) {
  OdometryIncrement increment;
  const double dx = to.x - from.x;
  const double dy = to.y - from.y;
  increment.trans = std::hypot(dx, dy);
  if (increment.trans >= min_translation) {
    increment.rot1 = AngleDifference(std::atan2(dy, dx), from.theta);
  }
  increment.rot2 = AngleDifference(to.theta, from.theta + increment.rot1);
  return increment;
}

Pose2 ApplyIncrement(const Pose2& pose, const OdometryIncrement& increment) {
  const double heading = pose.theta + increment.rot1;
  return Pose2(pose.x + increment.trans * std::cos(heading),
               pose.y + increment.trans * std::sin(heading),
               NormalizeAngle(heading + increment.rot2));
}

OdometryIncrement SampleIncrement(const OdometryIncrement& increment,
                                  const std::array<double, 4>& alphas, Rng& rng) {
  const auto [a1, a2, a3, a4] = alphas;
  const double rot1_sq = increment.rot1 * increment.rot1;
  const double rot2_sq = increment.rot2 * increment.rot2;
  const double trans_sq = increment.trans * increment.trans;
  // Three draws in a fixed order, whatever the motion, so that runs stay reproducible.
  const double e_rot1 = SampleWithVariance(a1 * rot1_sq + a2 * trans_sq, rng);
  const double e_trans = SampleWithVariance(a3 * trans_sq + a4 * (rot1_sq + rot2_sq), rng);
  const double e_rot2 = SampleWithVariance(a1 * rot2_sq + a2 * trans_sq, rng);
  return {increment.rot1 - e_rot1, increment.trans - e_trans, increment.rot2 - e_rot2};
}

OdometrySimulator::OdometrySimulator(const std::array<double, 4>& alphas, const Pose2& true_start,
                                     const OdometryScaleError& scale_error)
    : alphas_(alphas), scale_error_(scale_error), truth_(true_start), odometry_(true_start) {}

const Pose2& OdometrySimulator::Step(const Pose2& truth, Rng& rng) {
  OdometryIncrement increment = ComputeIncrement(truth_, truth);
  increment.rot1 *= 1.0 + scale_error_.turn;
  increment.trans *= 1.0 + scale_error_.distance;
  increment.rot2 *= 1.0 + scale_error_.turn;
  odometry_ = ApplyIncrement(odometry_, SampleIncrement(increment, alphas_, rng));
  truth_ = truth;
  return odometry_;
}

}  // namespace semchain::sim
