#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/pose2.h"
#include "core/rng.h"
#include "core/status.h"

// Pose hypotheses with a covariance and a weight: what a pre-localization (seed 000 §3.1, the
// semantic chain list) hands to AMCL, and the pose prior of the improved AMCL (seed 000 §3.2):
// particles are drawn as Gaussians around the hypotheses, and during the updates each particle's
// weight is multiplied by its match probability against them.
namespace semchain::localization {

struct PoseHypothesis {
  Pose2 pose;
  // Of (x, y, θ); nav2's initial_cov defaults: 0.5² m², 0.5² m², (π/12)² rad².
  Eigen::Matrix3d covariance = Eigen::Vector3d(0.25, 0.25, 0.0685389).asDiagonal();
  double weight = 1.0;  // relative; the list need not be normalised
};

// Checks a list: non-empty, finite, positive weights, symmetric positive-definite covariances.
Status ValidateHypotheses(const std::vector<PoseHypothesis>& hypotheses);

// Draws a pose from N(hypothesis.pose, hypothesis.covariance), the heading wrapped.
Pose2 SamplePose(const PoseHypothesis& hypothesis, Rng& rng);

// The prior of seed 000 §3.2: the match probability of a pose against a hypothesis list,
//   P(x) = max(floor, max_h (w_h / max w) · exp(−½ eₕᵀ Σₕ⁻¹ eₕ)),
// eₕ = (x − xₕ, y − yₕ, wrap(θ − θₕ)). A particle at a hypothesis keeps its weight, one far from
// all of them keeps 'floor' of it.
class PosePrior {
 public:
  // 'hypotheses' must pass ValidateHypotheses.
  PosePrior(const std::vector<PoseHypothesis>& hypotheses, double floor);
  double Probability(const Pose2& pose) const;
  const std::vector<PoseHypothesis>& hypotheses() const { return hypotheses_; }

 private:
  std::vector<PoseHypothesis> hypotheses_;
  std::vector<Eigen::Matrix3d> information_;  // Σₕ⁻¹
  std::vector<double> relative_weight_;
  double floor_;
};

}  // namespace semchain::localization
