#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "mapping/match_grid.h"

// Scan-to-map refinement with Ceres (seed 001 §2.2, Cartographer's CeresScanMatcher2D):
// argmin_T Σ (1 − M(S_i(T)))² on the bicubic-interpolated match grid (analytic Jacobian,
// OccupiedSpaceCost), starting from an initial pose (the branch-and-bound result or a prior).
namespace semchain::mapping {

struct CeresScanMatcherOptions {
  double occupied_space_weight = 1.0;
  // Cartographer also pulls the pose towards the initial estimate (its defaults 10 and 40 are
  // for a matcher seeded by odometry); 0 keeps the paper's cost alone.
  double translation_weight = 0.0;
  double rotation_weight = 0.0;
  int max_num_iterations = 20;
  // The refinement ends once an accepted step moves the pose by less than this (the norm of
  // (dx, dy, dθ), metres and radians): a tenth of a 5 cm cell. Ceres' own parameter tolerance
  // is relative to the pose's magnitude, i.e. to where the map's origin happens to be. Near the
  // optimum the steps shrink slowly (the cost is far from quadratic) and each costs two passes
  // over the returns: on 40 noiseless scans of the synthetic room started up to 2.5 cm off,
  // 5 mm stops after 3.8 iterations instead of 6.2 (1 mm) or 10.1 (Ceres' tolerances), 2.4 mm
  // on average from the full solve, 3.8 mm from the truth instead of 3.4 mm.
  // 0 leaves the stop to Ceres' tolerances.
  double min_step = 5e-3;

  bool Validate(std::string* error) const;
};

struct CeresMatchResult {
  Pose2 pose;
  double initial_cost = 0.0;  // Ceres' ½ Σ r² at the initial pose and at the result
  double final_cost = 0.0;
  int iterations = 0;
  bool converged = false;  // stopped on a tolerance or min_step, not on the iteration limit
};

// Refines 'initial' for 'points' (robot frame, metres) on 'grid'.
CeresMatchResult RefineWithCeres(const MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                                 const Pose2& initial, const CeresScanMatcherOptions& options = {});

// Mean bicubic-interpolated M over 'points' placed at 'pose' (one more pass over the points:
// the refinement does not compute it for callers that do not ask).
double MatchScore(const MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                  const Pose2& pose);

}  // namespace semchain::mapping
