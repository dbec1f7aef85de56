#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "mapping/match_grid.h"

// Scan-to-map refinement with Ceres (seed 001 §2.2, Cartographer's CeresScanMatcher2D):
// argmin_T Σ (1 − M(S_i(T)))² on the bicubic-interpolated match grid (analytic Jacobian,
// OccupiedSpaceCost), starting from an initial pose (the branch-and-bound result or a prior).
//
// The problem has three parameters and one block of residuals, so it is solved with
// ceres::TinySolver, Ceres' Levenberg–Marquardt for small dense problems: ceres::Solve spent
// about half of a refinement on its preprocessing, program and linear-solver set-up (lab_loop
// relocalizations: 95–160 µs per solve, 50–80 µs of it outside the passes over the returns).
namespace semchain::mapping {

struct CeresScanMatcherOptions {
  double occupied_space_weight = 1.0;
  int max_num_iterations = 20;
  // The solver works on the correction δ to the initial pose and stops when a step is smaller
  // than step_tolerance × (‖δ‖ + step_tolerance) (TinySolver's relative step test; the norm of
  // (dx, dy, dθ), metres and radians): with 0.03, below 3 % of the correction made so far plus
  // 0.9 mm, about 2 mm for the 2–3 cm a branch-and-bound cell leaves. Solving for δ rather than
  // the pose keeps the test independent of where the map's origin happens to be. Near the
  // optimum the steps shrink slowly (the cost is far from quadratic) and each costs two passes
  // over the returns: on 40 noiseless scans of the synthetic room started up to 2.5 cm off,
  // 4.7 iterations instead of 5.3 (TinySolver's cost-change test alone), 0.8 mm from that
  // solution, 3.5 mm from the truth instead of 3.4 (0.05: 3.3 iterations, 4.7 mm).
  double step_tolerance = 0.03;

  bool Validate(std::string* error) const;
};

struct CeresMatchResult {
  Pose2 pose;
  double initial_cost = 0.0;  // ½ Σ r² at the initial pose and at the result
  double final_cost = 0.0;
  int iterations = 0;
  bool converged = false;  // stopped on a tolerance, not on the iteration limit
};

// Refines 'initial' for 'points' (robot frame, metres) on 'grid'.
CeresMatchResult RefineWithCeres(const MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                                 const Pose2& initial, const CeresScanMatcherOptions& options = {});

// Mean bicubic-interpolated M over 'points' placed at 'pose' (one more pass over the points:
// the refinement does not compute it for callers that do not ask).
double MatchScore(const MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                  const Pose2& pose);

}  // namespace semchain::mapping
