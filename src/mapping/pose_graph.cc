#include "mapping/pose_graph.h"

#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>

#include "core/angles.h"
#include "core/check.h"
#include "mapping/dynamic_covariance_scaling.h"

namespace semchain::mapping {

bool PoseGraphOptions::Validate(std::string* error) const {
  if (!(dcs_phi > 0.0)) {
    *error = "dcs_phi must be positive";
    return false;
  }
  if (!(loop_loss_scale > 0.0)) {
    *error = "loop_loss_scale must be positive";
    return false;
  }
  if (max_iterations < 1) {
    *error = "max_iterations must be >= 1";
    return false;
  }
  if (threads < 1) {
    *error = "threads must be >= 1";
    return false;
  }
  return true;
}

namespace {

// An angle in (-π, π] for ceres::Jet as well as double.
template <typename T>
T NormalizeAngleT(const T& angle) {
  const T two_pi(2.0 * M_PI);
  return angle - two_pi * ceres::floor((angle + T(M_PI)) / two_pi);
}

// W with WᵀW the inverse of the edge's covariance: diag(1/σ), or L⁻¹ for a full Σ = LLᵀ.
Eigen::Matrix3d WhiteningOf(const PoseGraphEdge& edge) {
  if (edge.covariance.isZero()) return edge.sigmas.cwiseInverse().asDiagonal();
  const Eigen::LLT<Eigen::Matrix3d> llt(edge.covariance);
  SEMCHAIN_CHECK(llt.info() == Eigen::Success);
  return llt.matrixL().solve(Eigen::Matrix3d::Identity());
}

// r = W · (measured ⊖ (pose_from⁻¹ ⊕ pose_to)).
class RelativePoseCost {
 public:
  explicit RelativePoseCost(const PoseGraphEdge& edge)
      : measured_(edge.relative), whitening_(WhiteningOf(edge)) {}

  template <typename T>
  bool operator()(const T* const from, const T* const to, T* residuals) const {
    const T cos_from = ceres::cos(from[2]);
    const T sin_from = ceres::sin(from[2]);
    const T dx = to[0] - from[0];
    const T dy = to[1] - from[1];
    // 'to' in the frame of 'from'.
    const T x = cos_from * dx + sin_from * dy;
    const T y = -sin_from * dx + cos_from * dy;
    const T theta = to[2] - from[2];
    const T error[3] = {x - T(measured_.x), y - T(measured_.y),
                        NormalizeAngleT(theta - T(measured_.theta))};
    for (int row = 0; row < 3; ++row) {
      residuals[row] = T(whitening_(row, 0)) * error[0] + T(whitening_(row, 1)) * error[1] +
                       T(whitening_(row, 2)) * error[2];
    }
    return true;
  }

 private:
  Pose2 measured_;
  Eigen::Matrix3d whitening_;
};

}  // namespace

Eigen::Matrix3d CovarianceOf(const PoseGraphEdge& edge) {
  if (!edge.covariance.isZero()) return edge.covariance;
  return edge.sigmas.cwiseProduct(edge.sigmas).asDiagonal();
}

Eigen::Vector3d WhitenedResidual(const PoseGraphEdge& edge, const std::vector<Pose2>& poses) {
  const Pose2& a = poses[static_cast<std::size_t>(edge.from)];
  const Pose2& b = poses[static_cast<std::size_t>(edge.to)];
  const double from[3] = {a.x, a.y, a.theta};
  const double to[3] = {b.x, b.y, b.theta};
  Eigen::Vector3d residual;
  RelativePoseCost{edge}(from, to, residual.data());
  return residual;
}

namespace {

using Parameters = std::vector<std::array<double, 3>>;

// One Ceres solve of 'edges' over 'parameters' (updated in place), the loop closures through
// 'loop_loss' (may be null: squared).
ceres::Solver::Summary Solve(const std::vector<PoseGraphEdge>& edges,
                             ceres::LossFunction* loop_loss, const PoseGraphOptions& options,
                             Parameters* parameters) {
  ceres::Problem::Options problem_options;
  // The cost functions are owned by the problem; the loop-closure loss is the caller's.
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  for (const PoseGraphEdge& edge : edges) {
    if (edge.from == edge.to) continue;
    auto* cost =
        new ceres::AutoDiffCostFunction<RelativePoseCost, 3, 3, 3>(new RelativePoseCost(edge));
    problem.AddResidualBlock(cost, edge.loop_closure ? loop_loss : nullptr,
                             (*parameters)[static_cast<std::size_t>(edge.from)].data(),
                             (*parameters)[static_cast<std::size_t>(edge.to)].data());
  }
  if (!parameters->empty() && problem.HasParameterBlock(parameters->front().data())) {
    problem.SetParameterBlockConstant(parameters->front().data());
  }
  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.num_threads = options.threads;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  if (problem.NumResidualBlocks() > 0) ceres::Solve(solver_options, &problem, &summary);
  return summary;
}

}  // namespace

double LoopEdgeWeight(const PoseGraphOptions& options, double squared_norm) {
  const double scale = options.loop_loss_scale;
  switch (options.loop_loss) {
    case RobustLoss::kNone:
      return 1.0;
    case RobustLoss::kHuber:  // ρ' = a / |r| beyond the scale a
      return squared_norm <= scale * scale ? 1.0 : std::sqrt(scale / std::sqrt(squared_norm));
    case RobustLoss::kCauchy:  // ρ' = 1 / (1 + χ² / a²)
      return std::sqrt(1.0 / (1.0 + squared_norm / (scale * scale)));
    case RobustLoss::kDynamicCovarianceScaling:
      return DcsScale(squared_norm, options.dcs_phi);
  }
  return 1.0;
}

PoseGraphSolution OptimizePoseGraph(const std::vector<Pose2>& initial,
                                    const std::vector<PoseGraphEdge>& edges,
                                    const PoseGraphOptions& options) {
  std::string error;
  SEMCHAIN_CHECK(options.Validate(&error));
  const auto start = std::chrono::steady_clock::now();
  for (const PoseGraphEdge& edge : edges) {
    SEMCHAIN_CHECK(edge.from >= 0 && edge.to >= 0 &&
                   static_cast<std::size_t>(std::max(edge.from, edge.to)) < initial.size());
    SEMCHAIN_CHECK((edge.sigmas.array() > 0.0).all());
  }
  Parameters parameters;
  parameters.reserve(initial.size());
  for (const Pose2& pose : initial) parameters.push_back({pose.x, pose.y, pose.theta});

  ceres::HuberLoss huber(options.loop_loss_scale);
  ceres::CauchyLoss cauchy(options.loop_loss_scale);
  DynamicCovarianceScalingLoss dcs(options.dcs_phi);
  const bool switching = options.loop_loss == RobustLoss::kDynamicCovarianceScaling;
  ceres::LossFunction* loop_loss = nullptr;
  if (options.loop_loss == RobustLoss::kHuber || switching) loop_loss = &huber;
  if (options.loop_loss == RobustLoss::kCauchy) loop_loss = &cauchy;
  PoseGraphSolution solution;
  ceres::Solver::Summary summary = Solve(edges, loop_loss, options, &parameters);
  solution.initial_cost = summary.initial_cost;
  solution.iterations = static_cast<int>(summary.iterations.size());
  if (switching) {  // DCS from the Huber solution (PoseGraphOptions::loop_loss)
    summary = Solve(edges, &dcs, options, &parameters);
    solution.iterations += static_cast<int>(summary.iterations.size());
  }
  solution.final_cost = summary.final_cost;
  // No residual block: nothing to do, which is converged too.
  solution.converged = summary.termination_type == ceres::CONVERGENCE || summary.iterations.empty();
  solution.poses.reserve(parameters.size());
  for (const auto& p : parameters) solution.poses.emplace_back(p[0], p[1], NormalizeAngle(p[2]));
  solution.weights.reserve(edges.size());
  for (const PoseGraphEdge& edge : edges) {
    solution.weights.push_back(
        edge.loop_closure && edge.from != edge.to
            ? LoopEdgeWeight(options, WhitenedResidual(edge, solution.poses).squaredNorm())
            : 1.0);
  }
  solution.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return solution;
}

GatedPoseGraphSolution OptimizeRejectingInconsistent(const std::vector<Pose2>& initial,
                                                     const std::vector<PoseGraphEdge>& edges,
                                                     double max_residual_sigmas,
                                                     const PoseGraphOptions& options) {
  GatedPoseGraphSolution gated;
  std::vector<bool> kept(edges.size(), true);
  for (;;) {
    std::vector<PoseGraphEdge> active;
    std::vector<int> index;
    for (std::size_t e = 0; e < edges.size(); ++e) {
      if (!kept[e]) continue;
      active.push_back(edges[e]);
      index.push_back(static_cast<int>(e));
    }
    gated.solution = OptimizePoseGraph(initial, active, options);
    int worst = -1;
    double worst_norm = max_residual_sigmas;
    for (std::size_t a = 0; a < active.size(); ++a) {
      if (!active[a].loop_closure) continue;
      const double norm = WhitenedResidual(active[a], gated.solution.poses).norm();
      if (norm > worst_norm) {
        worst_norm = norm;
        worst = index[a];
      }
    }
    if (worst < 0) return gated;
    kept[static_cast<std::size_t>(worst)] = false;
    gated.rejected.push_back(worst);
  }
}

}  // namespace semchain::mapping
