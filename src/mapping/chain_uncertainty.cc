#include "mapping/chain_uncertainty.h"

#include <Eigen/Geometry>
#include <cmath>

#include "core/check.h"

namespace semchain::mapping {

ChainUncertainty::ChainUncertainty(const Pose2& first)
    : positions_{first.translation()},
      headings_{first.theta},
      sum_s_{0.0},
      sum_q_{0.0},
      sum_qp_{Eigen::Vector2d::Zero()},
      sum_qpp_{Eigen::Matrix2d::Zero()} {}

void ChainUncertainty::Append(const Pose2& pose, double sigma_meters, double sigma_radians) {
  positions_.push_back(pose.translation());
  headings_.push_back(pose.theta);
  translation_variance_.push_back(sigma_meters * sigma_meters);
  heading_variance_.push_back(sigma_radians * sigma_radians);
  sum_s_.emplace_back();
  sum_q_.emplace_back();
  sum_qp_.emplace_back();
  sum_qpp_.emplace_back();
  AccumulateEdge(translation_variance_.size() - 1);
}

void ChainUncertainty::Reposition(const std::vector<Pose2>& poses) {
  SEMCHAIN_CHECK(poses.size() == positions_.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    positions_[i] = poses[i].translation();
    headings_[i] = poses[i].theta;
  }
  for (std::size_t k = 0; k < translation_variance_.size(); ++k) AccumulateEdge(k);
}

void ChainUncertainty::AccumulateEdge(std::size_t k) {
  const double q = heading_variance_[k];
  const Eigen::Vector2d& p = positions_[k + 1];  // the node the heading error swings about
  sum_s_[k + 1] = sum_s_[k] + translation_variance_[k];
  sum_q_[k + 1] = sum_q_[k] + q;
  sum_qp_[k + 1] = sum_qp_[k] + q * p;
  sum_qpp_[k + 1] = sum_qpp_[k] + q * p * p.transpose();
}

Eigen::Matrix3d ChainUncertainty::Relative(int j, int i, int frame) const {
  SEMCHAIN_CHECK(0 <= j && j <= i && i < size() && 0 <= frame && frame < size());
  const auto a = static_cast<std::size_t>(j);
  const auto b = static_cast<std::size_t>(i);
  const double s = sum_s_[b] - sum_s_[a];
  const double q = sum_q_[b] - sum_q_[a];
  const Eigen::Vector2d qp = sum_qp_[b] - sum_qp_[a];
  const Eigen::Matrix2d qpp = sum_qpp_[b] - sum_qpp_[a];
  // Positions relative to node i keep the sums well conditioned far from the origin.
  const Eigen::Vector2d& pi = positions_[b];
  const Eigen::Vector2d lever = q * pi - qp;  // Σ q_k (p_i − p_{k+1})
  Eigen::Matrix2d m = q * pi * pi.transpose() - pi * qp.transpose() - qp * pi.transpose() + qpp;
  m = 0.5 * (m + m.transpose());
  Eigen::Matrix2d perpendicular;  // J, the 90° rotation
  perpendicular << 0.0, -1.0, 1.0, 0.0;
  Eigen::Matrix3d world = Eigen::Matrix3d::Zero();
  world.topLeftCorner<2, 2>() =
      s * Eigen::Matrix2d::Identity() + perpendicular * m * perpendicular.transpose();
  world.topRightCorner<2, 1>() = perpendicular * lever;
  world.bottomLeftCorner<1, 2>() = (perpendicular * lever).transpose();
  world(2, 2) = q;
  // Into the frame's node: its heading rotates the position block.
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  rotation.topLeftCorner<2, 2>() =
      Eigen::Rotation2Dd(-headings_[static_cast<std::size_t>(frame)]).toRotationMatrix();
  return rotation * world * rotation.transpose();
}

}  // namespace semchain::mapping
