#include "mapping/ceres_scan_matcher.h"

#include <ceres/ceres.h>

#include "core/angles.h"
#include "core/check.h"
#include "mapping/occupied_space_cost.h"

namespace semchain::mapping {

bool CeresScanMatcherOptions::Validate(std::string* error) const {
  if (!(occupied_space_weight > 0.0)) {
    *error = "occupied_space_weight must be positive";
    return false;
  }
  if (!(translation_weight >= 0.0 && rotation_weight >= 0.0)) {
    *error = "translation_weight and rotation_weight must be >= 0";
    return false;
  }
  if (max_num_iterations < 1) {
    *error = "max_num_iterations must be >= 1";
    return false;
  }
  if (!(min_step >= 0.0)) {
    *error = "min_step must be >= 0";
    return false;
  }
  return true;
}

namespace {

// Ends the solve once an accepted step is below CeresScanMatcherOptions::min_step.
class SmallStepStop : public ceres::IterationCallback {
 public:
  explicit SmallStepStop(double min_step) : min_step_(min_step) {}

  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    return summary.iteration > 0 && summary.step_is_successful && summary.step_norm < min_step_
               ? ceres::SOLVER_TERMINATE_SUCCESSFULLY
               : ceres::SOLVER_CONTINUE;
  }

 private:
  double min_step_;
};

}  // namespace

double MatchScore(const MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                  const Pose2& pose) {
  if (points.empty()) return 0.0;
  const OccupiedSpaceCost cost(grid, points, 1.0);
  std::vector<double> residuals(points.size());
  const double parameters[3] = {pose.x, pose.y, pose.theta};
  const double* blocks[1] = {parameters};
  cost.Evaluate(blocks, residuals.data(), nullptr);
  double sum = 0.0;
  const double scale = 1.0 / std::sqrt(static_cast<double>(points.size()));
  for (const double r : residuals) sum += 1.0 - r / scale;
  return sum / static_cast<double>(points.size());
}

CeresMatchResult RefineWithCeres(const MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                                 const Pose2& initial, const CeresScanMatcherOptions& options) {
  std::string error;
  SEMCHAIN_CHECK(options.Validate(&error));
  CeresMatchResult result;
  result.pose = initial;
  if (points.empty()) return result;
  double pose[3] = {initial.x, initial.y, initial.theta};
  ceres::Problem problem;
  problem.AddResidualBlock(new OccupiedSpaceCost(grid, points, options.occupied_space_weight),
                           nullptr, pose);
  if (options.translation_weight > 0.0 || options.rotation_weight > 0.0) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PoseDeltaCost, 3, 3>(new PoseDeltaCost(
                                 {initial.x, initial.y, initial.theta}, options.translation_weight,
                                 options.rotation_weight)),
                             nullptr, pose);
  }
  ceres::Solver::Options solver;
  // Three parameters: JᵀJ is 3 × 3 and well conditioned (metres and radians over returns
  // metres apart), cheaper to form and solve than the Householder QR of the N × 3 Jacobian.
  solver.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = options.max_num_iterations;
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  SmallStepStop stop(options.min_step);
  if (options.min_step > 0.0) solver.callbacks.push_back(&stop);
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  result.pose = Pose2(pose[0], pose[1], NormalizeAngle(pose[2]));
  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;
  result.iterations = static_cast<int>(summary.iterations.size());
  result.converged = summary.termination_type == ceres::CONVERGENCE ||
                     summary.termination_type == ceres::USER_SUCCESS;
  return result;
}

}  // namespace semchain::mapping
