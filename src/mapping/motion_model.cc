#include "mapping/motion_model.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <random>

#include "core/angles.h"
#include "core/check.h"

namespace semchain::mapping {

bool MotionModelOptions::Validate(std::string* error) const {
  if (!(translation_per_meter >= 0.0 && translation_per_radian >= 0.0 &&
        rotation_per_meter >= 0.0 && rotation_per_radian >= 0.0)) {
    *error = "motion noise coefficients must be >= 0";
    return false;
  }
  if (!(min_translation_sigma_meters > 0.0 && min_rotation_sigma_radians > 0.0)) {
    *error = "min_translation_sigma_meters and min_rotation_sigma_radians must be positive";
    return false;
  }
  return true;
}

MotionModel::MotionModel(const MotionModelOptions& options) : options_(options) {
  std::string error;
  SEMCHAIN_CHECK(options_.Validate(&error));
}

Eigen::Vector2d MotionModel::LinearSigmas(const Pose2& increment) const {
  const double distance = std::hypot(increment.x, increment.y);
  const double turn = std::abs(increment.theta);
  return {options_.translation_per_meter * distance + options_.translation_per_radian * turn,
          options_.rotation_per_meter * distance + options_.rotation_per_radian * turn};
}

Eigen::Vector3d MotionModel::Sigmas(const Pose2& increment) const {
  const Eigen::Vector2d sigmas = LinearSigmas(increment);
  const double translation = std::max(options_.min_translation_sigma_meters, sigmas.x());
  const double rotation = std::max(options_.min_rotation_sigma_radians, sigmas.y());
  return {translation, translation, rotation};
}

MotionStep MotionModel::Step(const Pose2& increment) const {
  const Eigen::Vector3d sigma = Sigmas(increment);
  return {increment, sigma.cwiseProduct(sigma).asDiagonal()};
}

Eigen::Matrix3d MotionModel::RawCovariance(const Pose2& increment) const {
  const Eigen::Vector2d sigmas = LinearSigmas(increment);
  const Eigen::Vector2d variances = sigmas.cwiseProduct(sigmas);
  return Eigen::Vector3d(variances.x(), variances.x(), variances.y()).asDiagonal();
}

void MotionModel::Accumulate(const Pose2& step, MotionStep* total) const {
  // Noise n = (u, φ) at the old end moves to the new end as step⁻¹ ⊕ n ⊕ step, which to first
  // order is (Rᵀ (u + φ J t), φ) with R, t the step's rotation and translation, J t = (-t_y, t_x).
  const double c = std::cos(step.theta), s = std::sin(step.theta);
  Eigen::Matrix3d transport;
  transport << c, s, c * -step.y + s * step.x,  //
      -s, c, -s * -step.y + c * step.x,         //
      0.0, 0.0, 1.0;
  total->covariance = transport * total->covariance * transport.transpose() + RawCovariance(step);
  total->increment = total->increment * step;
}

Eigen::Matrix3d MotionModel::Floored(const Eigen::Matrix3d& covariance) const {
  Eigen::Matrix3d floored = covariance;
  const double floor_xy = options_.min_translation_sigma_meters;
  const double floor_theta = options_.min_rotation_sigma_radians;
  floored(0, 0) = std::max(floored(0, 0), floor_xy * floor_xy);
  floored(1, 1) = std::max(floored(1, 1), floor_xy * floor_xy);
  floored(2, 2) = std::max(floored(2, 2), floor_theta * floor_theta);
  return floored;
}

Eigen::Vector3d MotionModel::Sigmas(const MotionStep& step) const {
  return Floored(step.covariance).diagonal().cwiseSqrt();
}

Pose2 MotionModel::Sample(const Pose2& previous, const MotionStep& step, Rng& rng) const {
  // For a diagonal covariance the factor is the σ's themselves (√(σ²) is exact), so one draw
  // over an increment is the same as drawing each axis by its σ.
  const Eigen::Matrix3d lower = Floored(step.covariance).llt().matrixL();
  std::normal_distribution<double> normal;
  // θ, y, x: the order in which earlier releases drew them, so a seed's maps stay the same.
  const double z_theta = normal(rng);
  const double z_y = normal(rng);
  const double z_x = normal(rng);
  const Eigen::Vector3d n = lower * Eigen::Vector3d(z_x, z_y, z_theta);
  return Predict(previous, step.increment) * Pose2(n.x(), n.y(), n.z());
}

double MotionModel::LogDensity(const Pose2& x, const Pose2& previous,
                               const MotionStep& step) const {
  const Pose2 error = Predict(previous, step.increment).Between(x);
  const Eigen::Matrix3d lower = Floored(step.covariance).llt().matrixL();
  const Eigen::Vector3d e =
      lower.triangularView<Eigen::Lower>().solve(Eigen::Vector3d(error.x, error.y, error.theta));
  return -0.5 * e.squaredNorm();
}

}  // namespace semchain::mapping
