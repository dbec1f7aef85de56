#include "mapping/annealing.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace semchain::mapping {

bool AnnealingOptions::Validate(std::string* error) const {
  if (rule != "auto" && rule != "fixed") {
    *error = "rule must be 'auto' or 'fixed', not '" + rule + "'";
    return false;
  }
  for (const double a : {alpha, motion_dominant_alpha, observation_dominant_alpha}) {
    if (!(a >= 0.0 && a <= 1.0)) {
      *error = "alpha values must be in [0, 1]";
      return false;
    }
  }
  if (!(flat_fraction > 0.0)) {
    *error = "flat_fraction must be positive";
    return false;
  }
  return true;
}

DominantModel ClassifyStep(const AnnealingOptions& options, const ProposalEvaluation& evaluation,
                           const ProposalOptions& proposal, const Eigen::Vector3d& motion_sigmas) {
  if (!evaluation.matched) return DominantModel::kMotion;
  const GaussianFit observation = FitProposal(evaluation, 1.0, 0.0, proposal);
  // Standard deviation of a uniform spread over ±w is w / √3; compare in units of the window.
  const Eigen::Vector3d scale(proposal.sample_window_meters, proposal.sample_window_meters,
                              proposal.sample_window_radians);
  const Eigen::Matrix3d normalized = scale.cwiseInverse().asDiagonal() * observation.covariance *
                                     scale.cwiseInverse().asDiagonal();
  const double largest =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(normalized).eigenvalues().maxCoeff();
  if (std::sqrt(std::max(largest, 0.0)) > options.flat_fraction / std::sqrt(3.0)) {
    return DominantModel::kMotion;
  }
  for (int i = 0; i < 3; ++i) {
    if (std::sqrt(observation.covariance(i, i)) > motion_sigmas[i]) return DominantModel::kMotion;
  }
  return DominantModel::kObservation;
}

double ChooseAlpha(const AnnealingOptions& options, const std::vector<DominantModel>& votes) {
  if (options.rule == "fixed") return options.alpha;
  const auto motion = std::count(votes.begin(), votes.end(), DominantModel::kMotion);
  return 2 * motion > static_cast<long>(votes.size()) ? options.motion_dominant_alpha
                                                      : options.observation_dominant_alpha;
}

}  // namespace semchain::mapping
