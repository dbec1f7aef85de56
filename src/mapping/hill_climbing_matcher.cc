#include "mapping/hill_climbing_matcher.h"

namespace semchain::mapping {

bool HillClimbingOptions::Validate(std::string* error) const {
  if (!(linear_step_meters > 0.0 && angular_step_radians > 0.0)) {
    *error = "linear_step_meters and angular_step_radians must be positive";
    return false;
  }
  if (refinements < 0 || max_evaluations < 1) {
    *error = "refinements must be >= 0 and max_evaluations >= 1";
    return false;
  }
  return true;
}

MatchResult HillClimb(const LikelihoodField& field, const MatchPoints& points, const Pose2& initial,
                      const HillClimbingOptions& options) {
  MatchResult best{initial, field.Evaluate(points, initial), 1};
  double linear = options.linear_step_meters;
  double angular = options.angular_step_radians;
  int refinement = 0;
  while (refinement <= options.refinements && best.evaluations < options.max_evaluations) {
    const Pose2 moves[6] = {{linear, 0, 0},  {-linear, 0, 0}, {0, linear, 0},
                            {0, -linear, 0}, {0, 0, angular}, {0, 0, -angular}};
    Pose2 candidate_best = best.pose;
    FieldEvaluation candidate_eval = best.evaluation;
    for (const Pose2& move : moves) {
      const Pose2 candidate(best.pose.x + move.x, best.pose.y + move.y,
                            best.pose.theta + move.theta);
      const FieldEvaluation eval = field.Evaluate(points, candidate);
      ++best.evaluations;
      if (eval.score > candidate_eval.score) {
        candidate_eval = eval;
        candidate_best = candidate;
      }
    }
    if (candidate_eval.score > best.evaluation.score) {
      best.pose = candidate_best;
      best.evaluation = candidate_eval;
    } else {
      linear *= 0.5;
      angular *= 0.5;
      ++refinement;
    }
  }
  return best;
}

}  // namespace semchain::mapping
