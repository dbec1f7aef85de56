#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "mapping/match_grid.h"

// Scan-to-map refinement with Ceres (seed 001 §2.2, Cartographer's CeresScanMatcher2D):
// argmin_T Σ (1 − M(S_i(T)))² on the bicubic-interpolated match grid, with automatic
// differentiation, starting from an initial pose (the branch-and-bound result or a prior).
namespace semchain::mapping {

struct CeresScanMatcherOptions {
  double occupied_space_weight = 1.0;
  // Cartographer also pulls the pose towards the initial estimate (its defaults 10 and 40 are
  // for a matcher seeded by odometry); 0 keeps the paper's cost alone.
  double translation_weight = 0.0;
  double rotation_weight = 0.0;
  int max_num_iterations = 20;
  // The refinement ends once an accepted step moves the pose by less than this (the norm of
  // (dx, dy, dθ), metres and radians): a fiftieth of a 5 cm cell. Ceres' own parameter
  // tolerance is relative to the pose's magnitude, i.e. to where the map's origin happens to be.
  // 0 leaves the stop to Ceres' tolerances (two more iterations on the FR079 benchmark, 0.2 mm).
  double min_step = 1e-3;

  bool Validate(std::string* error) const;
};

struct CeresMatchResult {
  Pose2 pose;
  double initial_cost = 0.0;  // Ceres' ½ Σ r² at the initial pose and at the result
  double final_cost = 0.0;
  double score = 0.0;  // mean bicubic-interpolated M over the points at 'pose'
  int iterations = 0;
  bool converged = false;  // stopped on a tolerance or min_step, not on the iteration limit
};

// Refines 'initial' for 'points' (robot frame, metres) on 'grid'.
CeresMatchResult RefineWithCeres(const MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                                 const Pose2& initial, const CeresScanMatcherOptions& options = {});

// Mean bicubic-interpolated M over 'points' placed at 'pose'.
double MatchScore(const MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                  const Pose2& pose);

}  // namespace semchain::mapping
