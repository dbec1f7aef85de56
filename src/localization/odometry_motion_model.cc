#include "localization/odometry_motion_model.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "core/angles.h"

namespace semchain::localization {
namespace {

double NoiseRotation(double rotation) {
  return std::min(std::abs(NormalizeAngle(rotation)), std::abs(AngleDifference(rotation, kPi)));
}

}  // namespace

OdometryMotion OdometryMotion::Between(const Pose2& from, const Pose2& to) {
  OdometryMotion u;
  const double dx = to.x - from.x;
  const double dy = to.y - from.y;
  u.trans = std::hypot(dx, dy);
  u.rot1 = u.trans < 0.01 ? 0.0 : AngleDifference(std::atan2(dy, dx), from.theta);
  u.rot2 = AngleDifference(AngleDifference(to.theta, from.theta), u.rot1);
  u.rot1_noise = NoiseRotation(u.rot1);
  u.rot2_noise = NoiseRotation(u.rot2);
  return u;
}

double OdometryMotionModel::Rot1Sigma(const OdometryMotion& u) const {
  return std::sqrt(noise_.alpha1 * u.rot1_noise * u.rot1_noise + noise_.alpha2 * u.trans * u.trans);
}

double OdometryMotionModel::TransSigma(const OdometryMotion& u) const {
  return std::sqrt(noise_.alpha3 * u.trans * u.trans +
                   noise_.alpha4 * (u.rot1_noise * u.rot1_noise + u.rot2_noise * u.rot2_noise));
}

double OdometryMotionModel::Rot2Sigma(const OdometryMotion& u) const {
  return std::sqrt(noise_.alpha1 * u.rot2_noise * u.rot2_noise + noise_.alpha2 * u.trans * u.trans);
}

Pose2 OdometryMotionModel::Sample(const Pose2& pose, const OdometryMotion& u, const Sigmas& sigmas,
                                  Rng& rng) {
  std::normal_distribution<double> normal;
  // Table 5.6 lines 5–7: perturb each component by a sample of its variance.
  const double rot1 = u.rot1 - sigmas.rot1 * normal(rng);
  const double trans = u.trans - sigmas.trans * normal(rng);
  const double rot2 = u.rot2 - sigmas.rot2 * normal(rng);
  return Pose2(pose.x + trans * std::cos(pose.theta + rot1),
               pose.y + trans * std::sin(pose.theta + rot1), pose.theta + rot1 + rot2);
}

}  // namespace semchain::localization
