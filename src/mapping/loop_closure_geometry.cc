#include "mapping/loop_closure_geometry.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "core/angles.h"

namespace semchain::mapping::internal {

Eigen::Vector3d LoopVariances(const LoopClosureOptions& options) {
  return Eigen::Vector3d(options.loop_sigma_meters * options.loop_sigma_meters,
                         options.loop_sigma_meters * options.loop_sigma_meters,
                         options.loop_sigma_radians * options.loop_sigma_radians);
}

PoseGraphEdge MotionEdge(int from, const Pose2& a, const Pose2& b,
                         const LoopClosureOptions& options) {
  PoseGraphEdge edge;
  edge.from = from;
  edge.to = from + 1;
  edge.relative = a.Between(b);
  const double distance = edge.relative.translation().norm();
  const double turn = std::abs(edge.relative.theta);
  const double xy = options.odometry_sigma_meters + options.odometry_sigma_per_meter * distance;
  const double theta =
      options.odometry_sigma_radians + options.odometry_sigma_radians_per_radian * turn;
  edge.sigmas = Eigen::Vector3d(xy, xy, theta);
  return edge;
}

bool LoosenSnap(const Pose2& local_step, const LoopClosureOptions& options, PoseGraphEdge* edge) {
  if (options.snap_sigmas <= 0.0) return false;
  const Eigen::Vector3d disagreement = PoseError(edge->relative, local_step).cwiseAbs();
  if ((disagreement.array() <= options.snap_sigmas * edge->sigmas.array()).all()) return false;
  const double xy = std::max(disagreement.x(), disagreement.y());
  edge->sigmas = edge->sigmas.cwiseMax(Eigen::Vector3d(xy, xy, disagreement.z()));
  return true;
}

RelativeUncertainty UncertaintyToSubmap(const ChainUncertainty& chain, int first, int anchor, int i,
                                        const LoopClosureOptions& options) {
  const int from = std::max(first, anchor);
  RelativeUncertainty uncertainty{chain.Relative(from, i, first), Eigen::Matrix3d::Zero()};
  if (from != first) uncertainty.fixed.diagonal() = LoopVariances(options);
  return uncertainty;
}

SearchWindow WindowFor(const Eigen::Matrix3d& covariance, const LoopClosureOptions& options) {
  SearchWindow window;
  const double linear_sigma =
      std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(covariance.topLeftCorner<2, 2>(),
                                                               Eigen::EigenvaluesOnly)
                    .eigenvalues()
                    .maxCoeff());
  window.linear_window_meters =
      std::clamp(options.window_sigmas * linear_sigma, options.linear_window_meters,
                 options.max_linear_window_meters);
  window.angular_window_radians =
      std::clamp(options.window_sigmas * std::sqrt(covariance(2, 2)),
                 options.angular_window_radians, options.max_angular_window_radians);
  return window;
}

Eigen::Vector3d PoseError(const Pose2& a, const Pose2& b) {
  return {a.x - b.x, a.y - b.y, NormalizeAngle(a.theta - b.theta)};
}

double SquaredMahalanobis(const Eigen::Vector3d& error, const Eigen::Matrix3d& covariance) {
  return error.dot(covariance.ldlt().solve(error));
}

double SquaredPairDisagreement(const PoseGraphEdge& a, const PoseGraphEdge& b,
                               const std::vector<Pose2>& estimate, const ChainUncertainty& chain,
                               const LoopClosureOptions& options) {
  const auto at = [&estimate](int node) -> const Pose2& {
    return estimate[static_cast<std::size_t>(node)];
  };
  const Pose2 implied = (at(a.from) * a.relative).Between(at(b.from) * b.relative);
  Eigen::Matrix3d covariance = chain.Relative(a.to, b.to);
  if (options.corridor_confirmation && a.from != b.from) {
    covariance += chain.Relative(std::min(a.from, b.from), std::max(a.from, b.from));
  }
  covariance.diagonal() += 2.0 * LoopVariances(options);
  return SquaredMahalanobis(PoseError(implied, at(a.to).Between(at(b.to))), covariance);
}

double MotionNoiseScale(const std::vector<Innovation>& innovations, double min_scale,
                        double max_scale) {
  constexpr double kChiSquared3Dof99 = 11.345;
  const auto worst = [&innovations](double scale) {
    double largest = 0.0;
    for (const Innovation& v : innovations) {
      largest = std::max(largest, SquaredMahalanobis(v.error, scale * v.motion + v.fixed));
    }
    return largest;
  };
  if (worst(min_scale) <= kChiSquared3Dof99) return min_scale;
  if (worst(max_scale) >= kChiSquared3Dof99) return max_scale;
  double low = std::log(min_scale), high = std::log(max_scale);
  for (int iteration = 0; iteration < 40; ++iteration) {
    const double middle = 0.5 * (low + high);
    (worst(std::exp(middle)) > kChiSquared3Dof99 ? low : high) = middle;
  }
  return std::exp(high);
}

std::vector<PoseGraphEdge> ScaledMotion(const std::vector<PoseGraphEdge>& edges, double scale,
                                        const std::vector<bool>& loosened) {
  std::vector<PoseGraphEdge> scaled = edges;
  const double factor = std::sqrt(scale);
  for (PoseGraphEdge& edge : scaled) {
    const auto from = static_cast<std::size_t>(edge.from);
    if (edge.loop_closure || (from < loosened.size() && loosened[from])) continue;
    edge.sigmas *= factor;
  }
  return scaled;
}

}  // namespace semchain::mapping::internal
