#pragma once

#include <string>

#include "core/pose2.h"
#include "mapping/hill_climbing_matcher.h"
#include "mapping/likelihood_field.h"
#include "mapping/prepared_scan.h"

// A sweep of the heading before local scan matching. Hill climbing on the likelihood field only
// reaches as far as its kernel (about ±1.5 cells around each endpoint): when the start's heading
// is off by more than a few degrees, the endpoints a few metres away all fall outside it, the
// score has no slope towards the right heading, and the match stays where it started. Wheel
// odometry is off by that much on fast turns (mit-csail: 20–25° between two processed scans, the
// odometry leading the laser), so the RBPF's proposal sweeps the heading first: the score at
// every heading step within ±window of the start (translation fixed), and the best heading is a
// second start for the hill climber. Translation errors of the same step are left to the hill
// climber: at the right heading the walls parallel to the error still match and pull.
namespace semchain::mapping {

struct HeadingSearchOptions {
  // The window is this many standard deviations of the motion model's heading noise, so that it
  // follows the turn (GMapping's stt) — wheel odometry's heading errors are heavier-tailed than
  // the Gaussian of the model; 5 is a useful value. 0 (the default) turns the sweep off: on the
  // raw logs it did not pay (docs/experiments.md, "SLAM": mit-csail 0.028 m with it, 0.030
  // without; ACES 0.21 m with it, 0.056 without).
  double window_sigmas = 0.0;
  double max_window_radians = 0.6;  // never wider than this (±34°)
  // Small enough that an endpoint 3–4 m away falls within the kernel at one of the steps.
  double step_radians = 0.02;
  // The match from the swept heading replaces the one from the start only when its score is this
  // many times higher: in corridors and rows of doors the field has several optima of similar
  // score within the window, and there the odometry's heading is the better guide.
  double min_score_ratio = 1.25;

  bool Validate(std::string* error) const;
};

struct HeadingSearchResult {
  Pose2 pose;          // 'start' with the best heading found
  double score = 0.0;  // the field's score there
  int evaluations = 0;
};

// Scores 'points' at 'start' rotated by every multiple of the step within ±window_radians (the
// start itself included) and returns the best.
HeadingSearchResult SearchHeading(const LikelihoodField& field, const MatchPoints& points,
                                  const Pose2& start, double window_radians, double step_radians);

// Hill climbing from 'start', and from the best heading of the sweep over
// ±min(max_window_radians, window_sigmas × heading_sigma) when that lies more than one angular
// step of the climber away; the second match wins only when it scores min_score_ratio times
// higher. With the sweep off (a window narrower than one step) this is HillClimb alone.
MatchResult MatchWithHeadingSearch(const LikelihoodField& field, const MatchPoints& points,
                                   const Pose2& start, const HillClimbingOptions& matcher,
                                   const HeadingSearchOptions& options, double heading_sigma);

}  // namespace semchain::mapping
