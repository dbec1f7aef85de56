#include "mapping/loop_closure_options.h"

namespace semchain::mapping {

bool LoopClosureOptions::Validate(std::string* error) const {
  if (!(submap_travel_meters > 0.0)) {
    *error = "submap_travel_meters must be positive";
    return false;
  }
  if (!(min_loop_travel_meters > 0.0)) {
    *error = "min_loop_travel_meters must be positive";
    return false;
  }
  if (search_every_nodes < 1) {
    *error = "search_every_nodes must be >= 1";
    return false;
  }
  if (max_built_submaps < 1) {
    *error = "max_built_submaps must be >= 1";
    return false;
  }
  if (!(max_built_submaps_megabytes > 0.0)) {
    *error = "max_built_submaps_megabytes must be positive";
    return false;
  }
  if (!(window_sigmas > 0.0)) {
    *error = "window_sigmas must be positive";
    return false;
  }
  if (!(snap_sigmas >= 0.0)) {
    *error = "snap_sigmas must be >= 0 (0: the filter's steps at the model's noise)";
    return false;
  }
  if (!(gate_sigmas >= 0.0)) {
    *error = "gate_sigmas must be >= 0 (0: no gate)";
    return false;
  }
  if (!(confirm_within_meters >= 0.0)) {
    *error = "confirm_within_meters must be >= 0";
    return false;
  }
  if (!(linear_window_meters > 0.0) || !(max_linear_window_meters >= linear_window_meters)) {
    *error = "linear windows must be positive and max_linear_window_meters >= linear_window_meters";
    return false;
  }
  if (!(angular_window_radians > 0.0) || !(max_angular_window_radians >= angular_window_radians)) {
    *error =
        "angular windows must be positive and max_angular_window_radians >= angular_window_radians";
    return false;
  }
  if (!(min_score > 0.0 && min_score <= 1.0)) {
    *error = "min_score must be in (0, 1]";
    return false;
  }
  if (!(odometry_sigma_meters > 0.0) || !(odometry_sigma_radians > 0.0) ||
      !(loop_sigma_meters > 0.0) || !(loop_sigma_radians > 0.0) ||
      !(odometry_sigma_per_meter >= 0.0) || !(odometry_sigma_radians_per_radian >= 0.0)) {
    *error = "sigmas must be positive";
    return false;
  }
  if (!(min_motion_noise_scale > 0.0) || !(max_motion_noise_scale >= min_motion_noise_scale)) {
    *error = "motion noise scales must be positive and max >= min";
    return false;
  }
  if (!(min_known_fraction >= 0.0 && min_known_fraction <= 1.0)) {
    *error = "min_known_fraction must be in [0, 1]";
    return false;
  }
  if (!(consistent_min_score >= 0.0 && consistent_min_score <= min_score)) {
    *error = "consistent_min_score must be in [0, min_score]";
    return false;
  }
  if (!(query_travel_meters >= 0.0) || !(query_cell_meters > 0.0)) {
    *error = "query_travel_meters must be >= 0 and query_cell_meters positive";
    return false;
  }
  if (online_lag_nodes < 0) {
    *error = "online_lag_nodes must be >= 0";
    return false;
  }
  if (!(follow_min_shift_meters > 0.0) || !(follow_min_turn_radians > 0.0)) {
    *error = "follow_min_shift_meters and follow_min_turn_radians must be positive";
    return false;
  }
  if (!(record_min_score > 0.0 && record_min_score <= 1.0)) {
    *error = "record_min_score must be in (0, 1]";
    return false;
  }
  if (!(max_residual_sigmas > 0.0)) {
    *error = "max_residual_sigmas must be positive";
    return false;
  }
  if (!submap_grid.Validate(error) || !match_grid.Validate(error) || !matcher.Validate(error) ||
      !refinement.Validate(error)) {
    return false;
  }
  if (match_covariance && !covariance.Validate(error)) return false;
  return optimizer.Validate(error);
}

}  // namespace semchain::mapping
