#pragma once

#include <string>

#include "mapping/occupancy_grid.h"

// Cell-by-cell Bayesian fusion of two occupancy grids (seed 004 eq. 10, after Kouroshi):
//   P = P_s P_m / (P_s P_m + (1 − P_s)(1 − P_m)),
// which for independent sensors and a uniform prior is the sum of the two log-odds. An unknown
// cell is P = 0.5 and leaves the other grid's value unchanged.
namespace semchain::mapping {

struct GridFusionOptions {
  // Each input probability is clamped to [min_probability, max_probability] before eq. 10,
  // which bounds how much one grid can say. The bounds are asymmetric on purpose: a lidar sees
  // one plane and a depth camera a height band, so "free" in one grid does not contradict
  // "occupied" in the other (seed 004's low obstacle B is free at the lidar plane). With the
  // defaults a confident obstacle of either grid survives a confident free cell of the other
  // (logit 0.98 + logit 0.15 = 2.2, P = 0.90), two free cells stay free (P = 0.03), and a free
  // cell known to one grid only is still below map_server's free threshold 0.196.
  double min_probability = 0.15;
  double max_probability = 0.98;

  bool Validate(std::string* error) const;
};

// Eq. 10 on two probabilities (after clamping them as 'options' says).
double FuseProbabilities(double p_a, double p_b, const GridFusionOptions& options = {});

// The fused grid of 'a' and 'b', which must have the same resolution (their origins may differ):
// a grid with a's options and origin holding every cell known to either grid, its log-odds from
// eq. 10 (clamped to a's max_abs_log_odds), hits and observations summed.
OccupancyGrid FuseGrids(const OccupancyGrid& a, const OccupancyGrid& b,
                        const GridFusionOptions& options = {});

}  // namespace semchain::mapping
