#include "localization/amcl_options.h"

namespace semchain::localization {
namespace {

bool Fail(std::string* error, const char* message) {
  *error = message;
  return false;
}

}  // namespace

bool PosePriorOptions::Validate(std::string* error) const {
  if (!(floor > 0.0 && floor <= 1.0)) return Fail(error, "pose_prior.floor must be in (0, 1]");
  return true;
}

bool FailureDetectorOptions::Validate(std::string* error) const {
  if (!(alpha_slow > 0.0 && alpha_fast > alpha_slow && alpha_fast <= 1.0)) {
    return Fail(error, "failure_detector: need 0 < alpha_slow < alpha_fast <= 1");
  }
  if (!(min_fast_slow_ratio >= 0.0 && min_mean_beam_likelihood >= 0.0)) {
    return Fail(error, "failure_detector thresholds must be >= 0");
  }
  if (consecutive_updates < 1)
    return Fail(error, "failure_detector.consecutive_updates must be >= 1");
  return true;
}

bool AmclOptions::Validate(std::string* error) const {
  if (!(alpha1 >= 0.0 && alpha2 >= 0.0 && alpha3 >= 0.0 && alpha4 >= 0.0)) {
    return Fail(error, "alpha1..alpha4 must be >= 0");
  }
  if (max_beams < 2) return Fail(error, "max_beams must be >= 2");
  if (!(laser_likelihood_max_dist > 0.0))
    return Fail(error, "laser_likelihood_max_dist must be > 0");
  if (!(z_hit >= 0.0 && z_short >= 0.0 && z_max >= 0.0 && z_rand >= 0.0) ||
      !(z_hit + z_short + z_max + z_rand > 0.0)) {
    return Fail(error, "z_hit, z_short, z_max, z_rand must be >= 0 and not all 0");
  }
  if (!(sigma_hit > 0.0 && lambda_short > 0.0)) {
    return Fail(error, "sigma_hit and lambda_short must be > 0");
  }
  if (min_particles < 1 || max_particles < min_particles) {
    return Fail(error, "need 1 <= min_particles <= max_particles");
  }
  if (!(pf_err > 0.0 && pf_z > 0.0)) return Fail(error, "pf_err and pf_z must be > 0");
  if (!(kld_bin_x > 0.0 && kld_bin_y > 0.0 && kld_bin_theta > 0.0)) {
    return Fail(error, "kld bin sizes must be > 0");
  }
  if (!(recovery_alpha_slow >= 0.0 && recovery_alpha_fast >= 0.0 && recovery_alpha_slow <= 1.0 &&
        recovery_alpha_fast <= 1.0)) {
    return Fail(error, "recovery_alpha_slow and recovery_alpha_fast must be in [0, 1]");
  }
  if (resample_interval < 1) return Fail(error, "resample_interval must be >= 1");
  if (!(update_min_d >= 0.0 && update_min_a >= 0.0)) {
    return Fail(error, "update_min_d and update_min_a must be >= 0");
  }
  if (!(convergence_distance > 0.0)) return Fail(error, "convergence_distance must be > 0");
  return pose_prior.Validate(error) && failure_detector.Validate(error);
}

}  // namespace semchain::localization
