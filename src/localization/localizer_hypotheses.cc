#include "localization/localizer_hypotheses.h"

#include <Eigen/Cholesky>
#include <cmath>

namespace semchain::localization {

std::vector<PoseHypothesis> ToHypotheses(const std::vector<PoseCandidate>& candidates) {
  std::vector<PoseHypothesis> hypotheses;
  for (const PoseCandidate& c : candidates) {
    // More objects in agreement, more weight; the laser fit separates look-alikes.
    hypotheses.push_back({c.pose, c.covariance, c.agreeing * (0.1 + c.laser_score)});
  }
  return hypotheses;
}

void KeepMostExplaining(std::vector<PoseCandidate>* candidates) {
  std::erase_if(*candidates, [best = candidates->front().agreeing](const PoseCandidate& c) {
    return c.agreeing < best;
  });
}

Eigen::Matrix3d TrackingCovariance() {
  return Eigen::Vector3d(0.05 * 0.05, 0.05 * 0.05, 0.03 * 0.03).asDiagonal();
}

Eigen::Matrix3d SampleableCovariance(const Eigen::Matrix3d& covariance) {
  const Eigen::Matrix3d symmetric = 0.5 * (covariance + covariance.transpose());
  const Eigen::Vector3d floor(1e-4, 1e-4, 1e-4);
  if (symmetric.allFinite() && (symmetric.diagonal().array() >= floor.array()).all() &&
      symmetric.llt().info() == Eigen::Success) {
    return symmetric;
  }
  Eigen::Vector3d diagonal = symmetric.diagonal();
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(diagonal[i]) || diagonal[i] < floor[i]) diagonal[i] = floor[i];
  }
  return diagonal.asDiagonal();
}

}  // namespace semchain::localization
