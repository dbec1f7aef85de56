#pragma once

#include <Eigen/Core>
#include <string>

#include "core/pose2.h"
#include "mapping/likelihood_field.h"
#include "mapping/prepared_scan.h"

// Final alignment of a scan on a map by Gauss-Newton on point-to-surface distances (point-to-
// line ICP against the map's obstacle means, Censi 2008 in spirit): each endpoint's residual
// is its signed distance to the surface through its nearest obstacle means along that
// surface's normal, down-weighted by a Huber kernel. Used after hill climbing, where the
// score's plateau near the optimum leaves a few millimetres of slack.
namespace semchain::mapping {

struct SurfaceRefinementOptions {
  bool enabled = true;
  int iterations = 8;
  double huber_meters = 0.02;
  // Stop when an iteration moves the pose less than this (metres, and radians × 1 m).
  double convergence_meters = 1e-4;
  // Reject the refinement (keep the initial pose) when it moves farther than this.
  double max_correction_meters = 0.1;
  // Use only endpoints whose surface is a line through two obstacle means. Point-to-point
  // matches at the ends of walls pull a scan back along the wall onto what is already mapped.
  bool lines_only = true;

  bool Validate(std::string* error) const;
};

struct RefinementResult {
  Pose2 pose;
  int correspondences = 0;
  bool converged = false;
};

// A Gaussian prior on the pose: its mean and standard deviations (x, y, θ) in its own frame.
// Along directions the scan does not constrain (a corridor's axis) the prior keeps the pose;
// elsewhere the scan dominates (a maximum a posteriori estimate).
struct PosePrior {
  Pose2 mean;
  Eigen::Vector3d sigmas = Eigen::Vector3d::Ones();
};

// Refines 'initial' so that 'points' (robot frame) lie on the surfaces of 'field', optionally
// pulled towards 'prior'.
RefinementResult RefineOnSurface(const LikelihoodField& field, const MatchPoints& points,
                                 const Pose2& initial, const SurfaceRefinementOptions& options,
                                 const PosePrior* prior = nullptr);

}  // namespace semchain::mapping
