#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mapping/proposal.h"

// Annealing of the mixed proposal (seed 003 eq. 6–7): the observation and motion likelihoods
// get exponents 1 - α and α, π'' ∝ p(z | m, x)^(1-α) p(x | x_{t-1}, u)^α. The paper takes
// α = 0.6 when the motion model dominates and α = 0.02 when the observation model is closer to
// the true distribution.
//
// Eq. 7 as printed weights with p(z | ·)^α p(x | ·)^(1-α), the exponents swapped with respect to
// eq. 6; with α = 0.02 that would make the weights ignore the laser. We weight with the
// normaliser of the tempered product of eq. 6 (the form of eq. 5), which is what the
// importance-sampling argument behind eq. 5 gives for the tempered proposal.
namespace semchain::mapping {

struct AnnealingOptions {
  bool enabled = false;
  // "fixed": always 'alpha'; "auto": per step, 'observation_dominant_alpha' when the laser
  // pins the pose down better than odometry, else 'motion_dominant_alpha'.
  std::string rule = "auto";
  double alpha = 0.6;
  double motion_dominant_alpha = 0.6;
  double observation_dominant_alpha = 0.02;
  // Auto rule: the observation is "flat" (uninformative along some direction) when the largest
  // standard deviation of its fitted Gaussian exceeds this fraction of a uniform spread over the
  // sample window.
  double flat_fraction = 0.7;

  bool Validate(std::string* error) const;
};

// Which model a particle's evidence favours at this step.
enum class DominantModel { kObservation, kMotion };

// The auto rule for one particle: the motion model dominates when the scan match was not
// trusted, when the observation-only Gaussian is flat within the window, or when it is wider
// than the motion noise along any axis.
DominantModel ClassifyStep(const AnnealingOptions& options, const ProposalEvaluation& evaluation,
                           const ProposalOptions& proposal, const Eigen::Vector3d& motion_sigmas);

// α for this step: fixed, or the majority of the particles' classifications (one α for all
// particles, so that their weights stay comparable).
double ChooseAlpha(const AnnealingOptions& options, const std::vector<DominantModel>& votes);

}  // namespace semchain::mapping
