#include "mapping/motion_model.h"

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

Eigen::Vector3d MotionModel::Sigmas(const Pose2& increment) const {
  const double distance = std::hypot(increment.x, increment.y);
  const double turn = std::abs(increment.theta);
  const double translation =
      std::max(options_.min_translation_sigma_meters,
               options_.translation_per_meter * distance + options_.translation_per_radian * turn);
  const double rotation =
      std::max(options_.min_rotation_sigma_radians,
               options_.rotation_per_meter * distance + options_.rotation_per_radian * turn);
  return {translation, translation, rotation};
}

Pose2 MotionModel::Sample(const Pose2& previous, const Pose2& increment, Rng& rng) const {
  const Eigen::Vector3d sigma = Sigmas(increment);
  std::normal_distribution<double> normal;
  const Pose2 noise(sigma.x() * normal(rng), sigma.y() * normal(rng), sigma.z() * normal(rng));
  return Predict(previous, increment) * noise;
}

double MotionModel::LogDensity(const Pose2& x, const Pose2& previous,
                               const Pose2& increment) const {
  const Eigen::Vector3d sigma = Sigmas(increment);
  const Pose2 error = Predict(previous, increment).Between(x);
  const Eigen::Vector3d e(error.x / sigma.x(), error.y / sigma.y(), error.theta / sigma.z());
  return -0.5 * e.squaredNorm();
}

}  // namespace semchain::mapping
