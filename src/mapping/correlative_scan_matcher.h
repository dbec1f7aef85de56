#pragma once

#include <string>

#include "core/pose2.h"
#include "mapping/hill_climbing_matcher.h"
#include "mapping/likelihood_field.h"
#include "mapping/prepared_scan.h"

// Exhaustive search of a pose window (the real-time correlative scan matcher of Olson 2009 and
// Cartographer, on our likelihood field): every heading on a grid of angular steps, every
// translation on a grid of linear steps, keep the best score; then hill climbing from the best
// cell refines below the grid. For initial errors beyond hill climbing's reach (relocalization
// with a prior, recovery after a failed match); the RBPF proposal uses hill climbing alone.
namespace semchain::mapping {

struct CorrelativeSearchOptions {
  double linear_window_meters = 0.3;    // search ±this in x and y
  double angular_window_radians = 0.2;  // and ±this in heading
  double linear_step_meters = 0.05;
  double angular_step_radians = 0.01;
  int beam_step = 2;  // the search scores every n-th return; the refinement all of them
  HillClimbingOptions refinement{0.025, 0.01, 6, 300};

  bool Validate(std::string* error) const;
};

// The best pose for 'scan' within the window around 'center' and its evaluation.
MatchResult CorrelativeSearch(const LikelihoodField& field, const PreparedScan& scan,
                              const Pose2& center, const CorrelativeSearchOptions& options,
                              double max_range_meters = 30.0);

}  // namespace semchain::mapping
