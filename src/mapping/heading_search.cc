#include "mapping/heading_search.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"

namespace semchain::mapping {

bool HeadingSearchOptions::Validate(std::string* error) const {
  if (!(window_sigmas >= 0.0 && max_window_radians >= 0.0 && max_window_radians <= 3.2)) {
    *error = "window_sigmas must be >= 0 and max_window_radians in [0, 3.2]";
    return false;
  }
  if (!(step_radians > 0.0) || !(min_score_ratio >= 1.0)) {
    *error = "step_radians must be positive and min_score_ratio >= 1";
    return false;
  }
  return true;
}

HeadingSearchResult SearchHeading(const LikelihoodField& field, const MatchPoints& points,
                                  const Pose2& start, double window_radians, double step_radians) {
  HeadingSearchResult best{start, field.Evaluate(points, start).score, 1};
  const int steps = static_cast<int>(std::floor(window_radians / step_radians));
  for (int i = 1; i <= steps; ++i) {
    for (const double sign : {-1.0, 1.0}) {
      const Pose2 candidate(start.x, start.y, start.theta + sign * i * step_radians);
      const double score = field.Evaluate(points, candidate).score;
      ++best.evaluations;
      if (score > best.score) {
        best.score = score;
        best.pose = candidate;
      }
    }
  }
  return best;
}

MatchResult MatchWithHeadingSearch(const LikelihoodField& field, const MatchPoints& points,
                                   const Pose2& start, const HillClimbingOptions& matcher,
                                   const HeadingSearchOptions& options, double heading_sigma) {
  const MatchResult match = HillClimb(field, points, start, matcher);
  const double window = std::min(options.max_window_radians, options.window_sigmas * heading_sigma);
  if (window < options.step_radians) return match;
  const HeadingSearchResult swept =
      SearchHeading(field, points, start, window, options.step_radians);
  if (std::abs(AngleDifference(swept.pose.theta, match.pose.theta)) <=
      matcher.angular_step_radians) {
    return match;
  }
  const MatchResult other = HillClimb(field, points, swept.pose, matcher);
  return other.evaluation.score > options.min_score_ratio * match.evaluation.score ? other : match;
}

}  // namespace semchain::mapping
