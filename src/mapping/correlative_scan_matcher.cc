#include "mapping/correlative_scan_matcher.h"

#include <cmath>

namespace semchain::mapping {

bool CorrelativeSearchOptions::Validate(std::string* error) const {
  if (!(linear_window_meters >= 0.0 && angular_window_radians >= 0.0 && linear_step_meters > 0.0 &&
        angular_step_radians > 0.0) ||
      beam_step < 1) {
    *error = "windows must be >= 0, steps positive and beam_step >= 1";
    return false;
  }
  return refinement.Validate(error);
}

MatchResult CorrelativeSearch(const LikelihoodField& field, const PreparedScan& scan,
                              const Pose2& center, const CorrelativeSearchOptions& options,
                              double max_range_meters) {
  const MatchPoints sparse = SelectMatchPoints(scan, max_range_meters, options.beam_step);
  const int linear_cells =
      static_cast<int>(std::ceil(options.linear_window_meters / options.linear_step_meters));
  const int angular_cells =
      static_cast<int>(std::ceil(options.angular_window_radians / options.angular_step_radians));
  MatchResult best{center, field.Evaluate(sparse, center), 1};
  for (int a = -angular_cells; a <= angular_cells; ++a) {
    const double theta = center.theta + a * options.angular_step_radians;
    for (int iy = -linear_cells; iy <= linear_cells; ++iy) {
      for (int ix = -linear_cells; ix <= linear_cells; ++ix) {
        const Pose2 candidate(center.x + ix * options.linear_step_meters,
                              center.y + iy * options.linear_step_meters, theta);
        const FieldEvaluation evaluation = field.Evaluate(sparse, candidate);
        ++best.evaluations;
        if (evaluation.score > best.evaluation.score) {
          best.pose = candidate;
          best.evaluation = evaluation;
        }
      }
    }
  }
  const MatchPoints all = SelectMatchPoints(scan, max_range_meters);
  MatchResult refined = HillClimb(field, all, best.pose, options.refinement);
  refined.evaluations += best.evaluations;
  return refined;
}

}  // namespace semchain::mapping
