#pragma once

#include <string>

#include "core/pose2.h"
#include "mapping/likelihood_field.h"
#include "mapping/prepared_scan.h"

// Local scan matching by hill climbing with decreasing steps (the scan matcher of GMapping's
// improved proposal, Grisetti et al. 2007): from the initial pose, try one step along ±x, ±y
// and ±θ, take the best improvement, and halve the steps when none improves.
namespace semchain::mapping {

struct HillClimbingOptions {
  double linear_step_meters = 0.05;    // first step (GMapping lstep)
  double angular_step_radians = 0.05;  // first step (GMapping astep)
  int refinements = 6;                 // how often the steps are halved before stopping
  int max_evaluations = 400;           // hard bound on likelihood-field evaluations

  bool Validate(std::string* error) const;
};

struct MatchResult {
  Pose2 pose;
  FieldEvaluation evaluation;  // at 'pose'
  int evaluations = 0;
};

// Aligns 'points' (robot frame) with 'field' starting from 'initial' and returns the pose of
// the highest score found.
MatchResult HillClimb(const LikelihoodField& field, const MatchPoints& points, const Pose2& initial,
                      const HillClimbingOptions& options);

}  // namespace semchain::mapping
