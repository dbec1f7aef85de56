#include "mapping/surface_refinement.h"

#include <Eigen/Cholesky>
#include <cmath>

#include "core/angles.h"

namespace semchain::mapping {

bool SurfaceRefinementOptions::Validate(std::string* error) const {
  if (iterations < 0 || !(huber_meters > 0.0) || !(convergence_meters > 0.0) ||
      !(max_correction_meters > 0.0)) {
    *error = "iterations must be >= 0 and huber, convergence and max correction positive";
    return false;
  }
  return true;
}

namespace {

// The standard deviation of a point-to-surface residual (range noise and map blur), which
// weighs the scan against a prior.
constexpr double kMeasurementSigma = 0.02;

// Adds the prior's information (rotated into the world frame) to the normal equations.
void AddPrior(const PosePrior& prior, const Pose2& pose, Eigen::Matrix3d* hessian,
              Eigen::Vector3d* gradient) {
  const double c = std::cos(prior.mean.theta), s = std::sin(prior.mean.theta);
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  rotation.topLeftCorner<2, 2>() << c, -s, s, c;
  const Eigen::Matrix3d information =
      rotation * prior.sigmas.cwiseInverse().cwiseAbs2().asDiagonal() * rotation.transpose();
  const Eigen::Vector3d error(pose.x - prior.mean.x, pose.y - prior.mean.y,
                              AngleDifference(pose.theta, prior.mean.theta));
  *hessian += information;
  *gradient += information * error;
}

// One Gauss-Newton step: the pose increment (x, y, θ) and the number of correspondences.
// Residuals are in metres.
Eigen::Vector3d Step(const LikelihoodField& field, const MatchPoints& points, const Pose2& pose,
                     double huber_cells, bool lines_only, const PosePrior* prior,
                     int* correspondences) {
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  const double inverse_resolution = field.inverse_resolution();
  const Eigen::Vector2d origin = field.grid().origin();
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  *correspondences = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d& p = points.points[i];
    const Eigen::Vector2d rotated(c * p.x() - s * p.y(), s * p.x() + c * p.y());
    const Eigen::Vector2d& d = points.directions[i];
    const Eigen::Vector2d g =
        (Eigen::Vector2d(pose.x, pose.y) + rotated - origin) * inverse_resolution;
    const LikelihoodField::Nearest nearest =
        field.FindNearest(g, Eigen::Vector2d(c * d.x() - s * d.y(), s * d.x() + c * d.y()));
    if (!nearest.found || (lines_only && !nearest.on_line)) continue;
    ++*correspondences;
    const double residual = nearest.normal.dot(g - nearest.anchor);  // cells
    // d(residual)/d(x, y, θ) in metres: the normal, and its product with R'(θ) p.
    const Eigen::Vector3d jacobian(nearest.normal.x(), nearest.normal.y(),
                                   nearest.normal.dot(Eigen::Vector2d(-rotated.y(), rotated.x())));
    const double weight =
        (std::abs(residual) <= huber_cells ? 1.0 : huber_cells / std::abs(residual)) /
        (kMeasurementSigma * kMeasurementSigma);
    hessian += weight * jacobian * jacobian.transpose();
    gradient += weight * (residual / inverse_resolution) * jacobian;
  }
  if (*correspondences < 3 && prior == nullptr) return Eigen::Vector3d::Zero();
  if (prior != nullptr) AddPrior(*prior, pose, &hessian, &gradient);
  hessian.diagonal() += Eigen::Vector3d::Constant(1e-6);
  return -hessian.ldlt().solve(gradient);
}

}  // namespace

RefinementResult RefineOnSurface(const LikelihoodField& field, const MatchPoints& points,
                                 const Pose2& initial, const SurfaceRefinementOptions& options,
                                 const PosePrior* prior) {
  RefinementResult result{initial, 0, false};
  const double huber_cells = options.huber_meters * field.inverse_resolution();
  Pose2 pose = initial;
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    const Eigen::Vector3d step =
        Step(field, points, pose, huber_cells, options.lines_only, prior, &result.correspondences);
    pose = Pose2(pose.x + step.x(), pose.y + step.y(), pose.theta + step.z());
    if (step.head<2>().norm() + std::abs(step.z()) < options.convergence_meters) {
      result.converged = true;
      break;
    }
  }
  const Pose2 correction = initial.Between(pose);
  if (std::hypot(correction.x, correction.y) + std::abs(correction.theta) >
      options.max_correction_meters) {
    return {initial, result.correspondences, false};
  }
  result.pose = pose;
  return result;
}

}  // namespace semchain::mapping
