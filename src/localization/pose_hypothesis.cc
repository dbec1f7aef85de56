#include "localization/pose_hypothesis.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <random>

#include "core/angles.h"
#include "core/check.h"

namespace semchain::localization {

Status ValidateHypotheses(const std::vector<PoseHypothesis>& hypotheses) {
  if (hypotheses.empty()) return Status::Error("no pose hypotheses");
  for (std::size_t i = 0; i < hypotheses.size(); ++i) {
    const PoseHypothesis& h = hypotheses[i];
    const std::string which = "pose hypothesis " + std::to_string(i) + ": ";
    if (!std::isfinite(h.pose.x) || !std::isfinite(h.pose.y) || !std::isfinite(h.pose.theta)) {
      return Status::Error(which + "pose is not finite");
    }
    if (!(h.weight > 0.0) || !std::isfinite(h.weight)) {
      return Status::Error(which + "weight must be positive");
    }
    if (!h.covariance.allFinite() || !h.covariance.isApprox(h.covariance.transpose(), 1e-9) ||
        h.covariance.llt().info() != Eigen::Success) {
      return Status::Error(which + "covariance must be symmetric positive-definite");
    }
  }
  return Status::Ok();
}

Pose2 SamplePose(const PoseHypothesis& hypothesis, Rng& rng) {
  const Eigen::Matrix3d l = hypothesis.covariance.llt().matrixL();
  std::normal_distribution<double> normal;
  // Drawn θ, y, x, one statement each: the order of a constructor's arguments is unspecified
  // (GCC evaluates them last to first, clang first to last), and a seed must give the same
  // particles with either compiler. Last to first is what GCC did when the seeded results
  // (and the AMCL regression fixture) were made.
  const double theta_draw = normal(rng);
  const double y_draw = normal(rng);
  const double x_draw = normal(rng);
  const Eigen::Vector3d e = l * Eigen::Vector3d(x_draw, y_draw, theta_draw);
  return Pose2(hypothesis.pose.x + e.x(), hypothesis.pose.y + e.y(), hypothesis.pose.theta + e.z());
}

PosePrior::PosePrior(const std::vector<PoseHypothesis>& hypotheses, double floor)
    : hypotheses_(hypotheses), floor_(floor) {
  SEMCHAIN_CHECK(ValidateHypotheses(hypotheses).ok());
  double max_weight = 0.0;
  for (const PoseHypothesis& h : hypotheses) max_weight = std::max(max_weight, h.weight);
  for (const PoseHypothesis& h : hypotheses) {
    information_.push_back(h.covariance.inverse());
    relative_weight_.push_back(h.weight / max_weight);
  }
}

double PosePrior::Probability(const Pose2& pose) const {
  double best = floor_;
  for (std::size_t i = 0; i < hypotheses_.size(); ++i) {
    const Pose2& h = hypotheses_[i].pose;
    const Eigen::Vector3d e(pose.x - h.x, pose.y - h.y, AngleDifference(pose.theta, h.theta));
    best = std::max(best, relative_weight_[i] * std::exp(-0.5 * e.dot(information_[i] * e)));
  }
  return best;
}

}  // namespace semchain::localization
