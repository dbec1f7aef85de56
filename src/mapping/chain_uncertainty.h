#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/pose2.h"

// How uncertain one node of a pose chain is relative to an earlier one when only the chain's
// own edges connect them: each edge k (node k to k + 1) adds an isotropic translation error of
// variance s_k and a heading error of variance q_k, and a heading error at edge k swings every
// later node about node k + 1. To first order the covariance of node i seen from node j is
//   C_xy = Σ s_k I + J M Jᵀ,   M = Σ q_k (p_i − p_{k+1})(p_i − p_{k+1})ᵀ,
//   C_xθ = Σ q_k J (p_i − p_{k+1}),   C_θθ = Σ q_k,   k = j … i − 1,
// J the 90° rotation. Expanding M into sums of q_k, q_k p_{k+1} and q_k p_{k+1} p_{k+1}ᵀ makes
// every pair (j, i) an O(1) difference of prefix sums. The pose graph uses it to size its
// loop-closure search window and to gate closures the motion since does not allow.
namespace semchain::mapping {

class ChainUncertainty {
 public:
  // Starts the chain at 'first' (the node every later one is measured from).
  explicit ChainUncertainty(const Pose2& first);

  // Appends node k + 1 at 'pose' (world frame), reached from node k with the given translation
  // and heading standard deviations.
  void Append(const Pose2& pose, double sigma_meters, double sigma_radians);

  // Replaces the nodes' poses (after an optimization moved them); the edges' variances stay.
  void Reposition(const std::vector<Pose2>& poses);

  int size() const { return static_cast<int>(positions_.size()); }

  // Covariance of node i's pose (x, y, θ) relative to node j ≤ i, expressed in node j's frame,
  // or in node 'frame''s when given.
  Eigen::Matrix3d Relative(int j, int i) const { return Relative(j, i, j); }
  Eigen::Matrix3d Relative(int j, int i, int frame) const;

 private:
  void AccumulateEdge(std::size_t k);  // prefix sums up to and including edge k

  std::vector<Eigen::Vector2d> positions_;
  std::vector<double> headings_;
  std::vector<double> translation_variance_;  // s_k per edge
  std::vector<double> heading_variance_;      // q_k per edge
  // Prefix sums over edges 0 … m − 1 (index m): Σ s, Σ q, Σ q p, Σ q p pᵀ.
  std::vector<double> sum_s_;
  std::vector<double> sum_q_;
  std::vector<Eigen::Vector2d> sum_qp_;
  std::vector<Eigen::Matrix2d> sum_qpp_;
};

}  // namespace semchain::mapping
