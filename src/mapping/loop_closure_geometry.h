#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/pose2.h"
#include "mapping/branch_and_bound_matcher.h"
#include "mapping/chain_uncertainty.h"
#include "mapping/loop_closure_options.h"
#include "mapping/pose_graph.h"

// The loop closer's (loop_closure.cc) edges and uncertainties: the motion and closure edges'
// noise, how far a node may lie from a submap (its search window), how far a closure lies from
// the graph's prediction or from another closure (the gate and the confirmations), and the
// motion noise scale the innovations call for. Math on poses and covariances alone, kept apart
// from the closer's state; not part of the API.
namespace semchain::mapping::internal {

// What an accepted closure said that the graph did not already know: its error against the
// graph's prediction and the two covariances that error had to be explained by.
struct Innovation {
  Eigen::Vector3d error;
  Eigen::Matrix3d motion;  // the motion edges' part, at their modelled variances
  Eigen::Matrix3d fixed;   // the closures' part
};

// The variances (x, y, θ) of a loop-closure edge.
Eigen::Vector3d LoopVariances(const LoopClosureOptions& options);

// The edge from node 'from' (the filter's pose 'a') to the next (pose 'b'), with standard
// deviations growing with its motion.
PoseGraphEdge MotionEdge(int from, const Pose2& a, const Pose2& b,
                         const LoopClosureOptions& options);

// Loosens 'edge' (a motion edge: the filter's step) when 'local_step', a local estimate of the
// same motion, lies more than snap_sigmas of the edge's standard deviations from it in x, y or
// θ: its standard deviations become at least the disagreement (x and y the larger of the two).
// Returns whether it did (LoopClosureOptions::snap_sigmas).
bool LoosenSnap(const Pose2& local_step, const LoopClosureOptions& options, PoseGraphEdge* edge);

// Uncertainty of node i relative to submap 'first', in the submap's frame: the motion edges'
// part, since the later of the submap and the last accepted closure ('anchor'; the closure ties
// the path before it to the map, up to the closure's own uncertainty), and that closure's part.
struct RelativeUncertainty {
  Eigen::Matrix3d motion = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d fixed = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d Total() const { return motion + fixed; }
};

RelativeUncertainty UncertaintyToSubmap(const ChainUncertainty& chain, int first, int anchor, int i,
                                        const LoopClosureOptions& options);

// The search window (its centre left to the caller) of a pose with this covariance:
// window_sigmas standard deviations, within the floors and caps of the options.
SearchWindow WindowFor(const Eigen::Matrix3d& covariance, const LoopClosureOptions& options);

// (x, y, θ) of 'a' minus those of 'b', the heading wrapped.
Eigen::Vector3d PoseError(const Pose2& a, const Pose2& b);

double SquaredMahalanobis(const Eigen::Vector3d& error, const Eigen::Matrix3d& covariance);

// Squared Mahalanobis distance between what two closures say of the motion from a.to to b.to
// (each places its node in the map) and what the chain says of it; closures to two submaps also
// carry the uncertainty of the chain between the submaps (first-order, summed).
double SquaredPairDisagreement(const PoseGraphEdge& a, const PoseGraphEdge& b,
                               const std::vector<Pose2>& estimate, const ChainUncertainty& chain,
                               const LoopClosureOptions& options);

// The smallest factor on the motion edges' variances under which every closure's innovation
// lies within the 99 % region of a 3-dof Gaussian (squared Mahalanobis distance 11.34), within
// [min_scale, max_scale]: a filter far better than the model (its closures land where it
// predicts) gets a stiffer chain, one that drifts more a looser one.
double MotionNoiseScale(const std::vector<Innovation>& innovations, double min_scale,
                        double max_scale);

// 'edges' with the motion edges' standard deviations multiplied by sqrt(scale), but for those
// from the nodes 'loosened' marks (indexed by the edge's 'from'; may be shorter): their
// standard deviations are a measured disagreement (LoosenSnap), not the model's noise.
std::vector<PoseGraphEdge> ScaledMotion(const std::vector<PoseGraphEdge>& edges, double scale,
                                        const std::vector<bool>& loosened = {});

}  // namespace semchain::mapping::internal
