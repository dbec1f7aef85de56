#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/pose2.h"

// Sparse pose adjustment of a 2D pose graph (Konolige et al., "Efficient Sparse Pose Adjustment
// for 2D Mapping", IROS 2010; Cartographer's optimization problem): nodes are robot poses, an
// edge says where node 'to' is seen from node 'from' with a Gaussian uncertainty, and the
// optimizer finds the poses that best agree with every edge. Loop-closure edges go through a
// robust loss, so that one wrong closure cannot pull the graph with more than a bounded force,
// and closures the others contradict are found by their residuals and dropped
// (OptimizeRejectingInconsistent) or, with dynamic covariance scaling, switched off within the
// optimization itself; the first node is held fixed (the graph's frame).
namespace semchain::mapping {

struct PoseGraphEdge {
  int from = 0;
  int to = 0;
  Pose2 relative;  // pose of 'to' in the frame of 'from'
  // Standard deviations of the relative pose's x, y (metres) and θ (radians).
  Eigen::Vector3d sigmas = Eigen::Vector3d(0.05, 0.05, 0.01);
  // When not zero, the full covariance of (x, y, θ), used instead of 'sigmas': a closure
  // matched down a corridor is certain across it and not along it (LoopClosureOptions::
  // match_covariance).
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  bool loop_closure = false;
  int id = -1;  // the caller's label (e.g. which loop-closure candidate the edge came from)
};

enum class RobustLoss {
  kNone,    // squared residuals
  kHuber,   // linear beyond the scale: bounded pull, still convex (converges from far away)
  kCauchy,  // pull falls off beyond the scale (stalls far from a large correction)
  // Dynamic covariance scaling (dynamic_covariance_scaling.h): a closure the others contradict
  // is switched off (its scale s falls towards 0) and adds at most 3Φ to the cost. DCS is not
  // convex: a right closure that starts tens of σ off (after a long loop) would be switched off
  // before the graph moves, so the graph is first solved with the Huber loss (loop_loss_scale),
  // which pulls it most of the way, and then with DCS from there.
  kDynamicCovarianceScaling,
};

struct PoseGraphOptions {
  // Loss on loop-closure edges and its scale, in standard deviations of the whitened residual.
  // Huber, as Cartographer: a correct closure after a long loop starts tens of σ off and must
  // still pull the graph all the way; Cauchy would treat it as an outlier.
  RobustLoss loop_loss = RobustLoss::kHuber;
  double loop_loss_scale = 3.0;
  // Φ of dynamic covariance scaling, in squared whitened residual (χ²): a closure with χ² ≤ Φ
  // keeps its full weight, one with χ² = 3Φ half of it, one with χ² = 19Φ a tenth.
  double dcs_phi = 5.0;
  int max_iterations = 50;
  int threads = 1;
  bool Validate(std::string* error) const;
};

struct PoseGraphSolution {
  std::vector<Pose2> poses;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  int iterations = 0;
  bool converged = false;
  double seconds = 0.0;
  // One per edge given, in their order: LoopEdgeWeight of the loop closures at 'poses', 1 for
  // the other edges.
  std::vector<double> weights;
};

// Optimizes 'initial' (one pose per node) under 'edges' (node indices within 'initial').
PoseGraphSolution OptimizePoseGraph(const std::vector<Pose2>& initial,
                                    const std::vector<PoseGraphEdge>& edges,
                                    const PoseGraphOptions& options = {});

struct GatedPoseGraphSolution {
  PoseGraphSolution solution;
  std::vector<int> rejected;  // indices into the edges of the loop closures dropped
};

// The weight 'options'' loop-closure loss gives an edge whose squared whitened residual is
// 'squared_norm': sqrt(ρ'(χ²)), the factor iteratively reweighted least squares scales its
// residual by (1 within the loss's scale; for dynamic covariance scaling its s, for no loss 1).
double LoopEdgeWeight(const PoseGraphOptions& options, double squared_norm);

// Optimizes, then drops the loop closure with the largest whitened residual norm while it
// exceeds 'max_residual_sigmas' (the others contradict it) and optimizes again, from 'initial'.
GatedPoseGraphSolution OptimizeRejectingInconsistent(const std::vector<Pose2>& initial,
                                                     const std::vector<PoseGraphEdge>& edges,
                                                     double max_residual_sigmas,
                                                     const PoseGraphOptions& options = {});

// The edge's covariance of (x, y, θ): its 'covariance', or diag(sigmas²) when that is zero.
Eigen::Matrix3d CovarianceOf(const PoseGraphEdge& edge);

// The edge's residual at 'poses' whitened by its sigmas: (Δx/σx, Δy/σy, Δθ/σθ) of the measured
// relative pose against the one 'poses' give, Δ in the frame of 'from' (with a covariance Σ,
// L⁻¹Δ for Σ = LLᵀ, so that its squared norm is ΔᵀΣ⁻¹Δ).
Eigen::Vector3d WhitenedResidual(const PoseGraphEdge& edge, const std::vector<Pose2>& poses);

}  // namespace semchain::mapping
