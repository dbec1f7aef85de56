#include "mapping/odometry_perturbation.h"

#include <cmath>
#include <random>

#include "core/rng.h"

namespace semchain::mapping {

bool OdometryPerturbationOptions::Validate(std::string* error) const {
  if (!(translation_per_meter >= 0.0 && translation_per_radian >= 0.0 &&
        rotation_per_meter >= 0.0 && rotation_per_radian >= 0.0)) {
    *error = "odometry noise coefficients must be >= 0";
    return false;
  }
  if (!(std::abs(distance_scale_error) < 0.5 && std::abs(turn_scale_error) < 0.5)) {
    *error = "scale errors must be within ±0.5";
    return false;
  }
  return true;
}

PerturbedLog PerturbOdometry(const carmen::Log& log, const OdometryPerturbationOptions& options) {
  PerturbedLog result{log, {}};
  Rng rng = MakeRng(options.seed, 17);
  std::normal_distribution<double> normal;
  bool first = true;
  Pose2 previous_truth, odometry;
  for (carmen::Record& record : result.log.records) {
    auto* laser = std::get_if<carmen::Laser>(&record);
    if (laser == nullptr) continue;
    StampedScan& scan = laser->scan;
    const Pose2 offset = scan.LaserOffset();
    const Pose2 truth = scan.odometry;
    if (first) {
      odometry = truth;
      first = false;
    } else {
      const Pose2 d = previous_truth.Between(truth);
      const double distance = std::hypot(d.x, d.y), turn = std::abs(d.theta);
      const double sigma_xy =
          options.translation_per_meter * distance + options.translation_per_radian * turn;
      const double sigma_theta =
          options.rotation_per_meter * distance + options.rotation_per_radian * turn;
      const double scale = 1.0 + options.distance_scale_error;
      // θ, y, x, one statement each: a constructor's arguments are evaluated in an unspecified
      // order (GCC last to first, as the published figures were made; clang first to last).
      const double theta_noise = sigma_theta * normal(rng);
      const double y_noise = sigma_xy * normal(rng);
      const double x_noise = sigma_xy * normal(rng);
      odometry = odometry * Pose2(d.x * scale + x_noise, d.y * scale + y_noise,
                                  d.theta * (1.0 + options.turn_scale_error) + theta_noise);
    }
    previous_truth = truth;
    result.truth.push_back({scan.scan.timestamp, truth});
    scan.odometry = odometry;
    scan.laser_pose = odometry * offset;
  }
  return result;
}

}  // namespace semchain::mapping
