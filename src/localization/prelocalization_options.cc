#include "localization/prelocalization_options.h"

namespace semchain::localization {

bool PreLocalizationOptions::Validate(std::string* error) const {
  if (!(distance_tolerance > 0.0 && distance_tolerance < 1.0)) {
    *error = "distance_tolerance (alpha) must be in (0, 1)";
    return false;
  }
  if (!(distance_slack >= 0.0)) {
    *error = "distance_slack must be >= 0";
    return false;
  }
  if (!(unknown_reach >= 0.0)) {
    *error = "unknown_reach must be >= 0";
    return false;
  }
  if (!(heading_agreement > 0.0) || !(agreement_radius > 0.0) || max_hypotheses < 1 ||
      !(position_std_base > 0.0) || !(heading_std > 0.0) || clearance < 0.0 ||
      !(centre_std_base > 0.0)) {
    *error = "tolerances, standard deviations and max_hypotheses must be positive";
    return false;
  }
  if (!(laser_refine_max_shift >= 0.0) || !(laser_refine_max_turn >= 0.0)) {
    *error = "laser_refine_max_shift and laser_refine_max_turn must be >= 0";
    return false;
  }
  if (!(look_alike_laser_margin >= 0.0) || !(distinct_place_distance > 0.0) ||
      !(distinct_place_heading > 0.0)) {
    *error =
        "look_alike_laser_margin must be >= 0, distinct_place_distance and "
        "distinct_place_heading > 0";
    return false;
  }
  return true;
}

}  // namespace semchain::localization
