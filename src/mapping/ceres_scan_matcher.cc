#include "mapping/ceres_scan_matcher.h"

#include <ceres/tiny_solver.h>

#include "core/angles.h"
#include "core/check.h"
#include "mapping/occupied_space_cost.h"

namespace semchain::mapping {

bool CeresScanMatcherOptions::Validate(std::string* error) const {
  if (!(occupied_space_weight > 0.0)) {
    *error = "occupied_space_weight must be positive";
    return false;
  }
  if (max_num_iterations < 1) {
    *error = "max_num_iterations must be >= 1";
    return false;
  }
  if (!(step_tolerance >= 0.0)) {
    *error = "step_tolerance must be >= 0";
    return false;
  }
  return true;
}

namespace {

// The occupied-space cost as a function of the correction δ to the initial pose, for TinySolver
// (pose = initial + δ, so the Jacobians are the same).
class CorrectionCost {
 public:
  using Scalar = double;
  enum { NUM_RESIDUALS = Eigen::Dynamic, NUM_PARAMETERS = 3 };

  CorrectionCost(const OccupiedSpaceCost& cost, const Pose2& initial)
      : cost_(cost), initial_(initial.x, initial.y, initial.theta) {}

  int NumResiduals() const { return cost_.NumResiduals(); }

  bool operator()(const double* correction, double* residuals, double* jacobian) const {
    const Eigen::Vector3d pose = initial_ + Eigen::Map<const Eigen::Vector3d>(correction);
    return cost_(pose.data(), residuals, jacobian);
  }

 private:
  const OccupiedSpaceCost& cost_;
  Eigen::Vector3d initial_;
};

}  // namespace

double MatchScore(const MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                  const Pose2& pose) {
  if (points.empty()) return 0.0;
  const OccupiedSpaceCost cost(grid, points, 1.0);
  std::vector<double> residuals(points.size());
  const double parameters[3] = {pose.x, pose.y, pose.theta};
  cost(parameters, residuals.data(), nullptr);
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
  const OccupiedSpaceCost cost(grid, points, options.occupied_space_weight);
  const CorrectionCost correction_cost(cost, initial);
  // Value-initialized: TinySolver leaves cost_ unset until Solve sets it, which GCC cannot always
  // see (-Wmaybe-uninitialized, depending on what is inlined beside it).
  ceres::TinySolver<CorrectionCost> solver{};
  // TinySolver counts the evaluation at the start as an iteration.
  solver.options.max_num_iterations = options.max_num_iterations + 1;
  solver.options.parameter_tolerance = options.step_tolerance;
  Eigen::Vector3d correction = Eigen::Vector3d::Zero();
  const auto& summary = solver.Solve(correction_cost, &correction);
  result.pose = Pose2(initial.x + correction.x(), initial.y + correction.y(),
                      NormalizeAngle(initial.theta + correction.z()));
  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;
  result.iterations = summary.iterations;
  result.converged = summary.status != ceres::TinySolver<CorrectionCost>::HIT_MAX_ITERATIONS;
  return result;
}

}  // namespace semchain::mapping
