#include "localization/scan_tracking.h"

#include <ceres/tiny_solver.h>

#include <algorithm>
#include <cmath>

#include "core/angles.h"
#include "core/check.h"
#include "mapping/ceres_scan_matcher.h"
#include "mapping/match_grid.h"
#include "mapping/occupied_space_cost.h"

namespace semchain::localization {

bool ScanTrackingOptions::Validate(std::string* error) const {
  if (!(min_score >= 0.0 && min_score <= confident_score && confident_score <= 1.0)) {
    *error = "scan_tracking: need 0 <= min_score <= confident_score <= 1";
    return false;
  }
  if (!(min_ratio >= 0.0 && min_ratio <= confident_ratio && confident_ratio <= 1.0)) {
    *error = "scan_tracking: need 0 <= min_ratio <= confident_ratio <= 1";
    return false;
  }
  if (!(initial_typical_score > 0.0 && initial_typical_score <= 1.0 && typical_score_gain > 0.0 &&
        typical_score_gain <= 1.0)) {
    *error = "scan_tracking: initial_typical_score and typical_score_gain must be in (0, 1]";
    return false;
  }
  if (!(point_spacing_meters >= 0.0)) {
    *error = "scan_tracking.point_spacing_meters must be >= 0";
    return false;
  }
  if (!(translation_weight >= 0.0 && rotation_weight >= 0.0)) {
    *error = "scan_tracking: prior weights must be >= 0";
    return false;
  }
  if (!(start_max_sigma_meters > 0.0 && start_max_sigma_radians > 0.0)) {
    *error = "scan_tracking: start_max_sigma_meters and start_max_sigma_radians must be > 0";
    return false;
  }
  if (max_missed_scans < 1) {
    *error = "scan_tracking.max_missed_scans must be >= 1";
    return false;
  }
  if (!(search_margin_ratio >= 1.0)) {
    *error = "scan_tracking.search_margin_ratio must be >= 1";
    return false;
  }
  if (!(search_min_ratio >= 0.0 && search_min_ratio <= 1.0 && search_min_score >= 0.0 &&
        search_min_score <= 1.0)) {
    *error = "scan_tracking: need 0 <= search_min_ratio <= 1 and 0 <= search_min_score <= 1";
    return false;
  }
  if (!(max_correction_meters > 0.0 && max_correction_radians > 0.0 &&
        search_linear_window_meters >= 0.0 && search_angular_window_radians >= 0.0)) {
    *error = "scan_tracking: corrections must be > 0 and search windows >= 0";
    return false;
  }
  return true;
}

namespace {

bool Within(const Pose2& a, const Pose2& b, double meters, double radians) {
  return (a.translation() - b.translation()).norm() <= meters &&
         std::abs(AngleDifference(a.theta, b.theta)) <= radians;
}

// The occupied-space residuals of the returns and the prior's three, as functions of the
// correction δ to the prediction (TinySolver's layout: N + 3 residuals, Jacobian column-major).
class PriorCost {
 public:
  using Scalar = double;
  enum { NUM_RESIDUALS = Eigen::Dynamic, NUM_PARAMETERS = 3 };

  PriorCost(const mapping::OccupiedSpaceCost& cost, const Pose2& prediction,
            const ScanTrackingOptions& options)
      : cost_(cost),
        prediction_(prediction.x, prediction.y, prediction.theta),
        weights_(options.translation_weight, options.translation_weight, options.rotation_weight) {}

  int NumResiduals() const { return cost_.NumResiduals() + 3; }

  bool operator()(const double* correction, double* residuals, double* jacobian) const {
    const Eigen::Map<const Eigen::Vector3d> delta(correction);
    const Eigen::Vector3d pose = prediction_ + delta;
    const int n = cost_.NumResiduals();
    if (jacobian == nullptr) {
      if (!cost_(pose.data(), residuals, nullptr)) return false;
    } else {
      points_jacobian_.resize(static_cast<std::size_t>(3 * n));
      if (!cost_(pose.data(), residuals, points_jacobian_.data())) return false;
      const int rows = n + 3;
      for (int column = 0; column < 3; ++column) {
        std::copy_n(points_jacobian_.data() + column * n, n, jacobian + column * rows);
        for (int k = 0; k < 3; ++k) jacobian[column * rows + n + k] = k == column ? weights_[k] : 0;
      }
    }
    for (int k = 0; k < 3; ++k) residuals[n + k] = weights_[k] * delta[k];
    return true;
  }

 private:
  const mapping::OccupiedSpaceCost& cost_;
  Eigen::Vector3d prediction_;
  Eigen::Vector3d weights_;
  mutable std::vector<double> points_jacobian_;
};

// 'prediction' refined for 'points' on 'grid' under the prior.
Pose2 RefineWithPrior(const mapping::MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                      const Pose2& prediction, const ScanTrackingOptions& options) {
  const mapping::CeresScanMatcherOptions ceres;  // the relocalizer's iterations and tolerance
  const mapping::OccupiedSpaceCost cost(grid, points, ceres.occupied_space_weight);
  const PriorCost prior_cost(cost, prediction, options);
  ceres::TinySolver<PriorCost> solver{};
  solver.options.max_num_iterations = ceres.max_num_iterations + 1;
  solver.options.parameter_tolerance = ceres.step_tolerance;
  Eigen::Vector3d correction = Eigen::Vector3d::Zero();
  solver.Solve(prior_cost, &correction);
  return Pose2(prediction.x + correction.x(), prediction.y + correction.y(),
               NormalizeAngle(prediction.theta + correction.z()));
}

}  // namespace

ScanTrackingOptions ScanTrackingThresholds(const ScanTrackingOptions& options, double typical) {
  ScanTrackingOptions adjusted = options;
  adjusted.confident_score =
      std::clamp(options.confident_ratio * typical, options.min_score, options.confident_score);
  adjusted.min_score =
      std::clamp(options.min_ratio * typical, options.min_score, adjusted.confident_score);
  adjusted.search_min_score =
      std::max({options.search_min_ratio * typical, options.search_min_score, adjusted.min_score});
  return adjusted;
}

ScanTrackingResult TrackScan(const ScanMatchRelocalizer& matcher,
                             const std::vector<Eigen::Vector2d>& points,
                             const std::vector<Pose2>& predictions,
                             const ScanTrackingOptions& options) {
  SEMCHAIN_CHECK(!predictions.empty());
  ScanTrackingResult result;
  if (points.empty()) return result;
  const auto score_of = [&](const Pose2& pose) {
    return mapping::CellScore(matcher.grid(), points, pose);
  };
  // Keeps 'pose' when its 'score' is better than the best so far.
  const auto consider = [&](const Pose2& pose, double score) {
    if (score <= result.score) return;
    result.score = score;
    result.pose = pose;
    result.matched = score >= options.min_score;
  };
  for (const Pose2& prediction : predictions) {
    const Pose2 refined = RefineWithPrior(matcher.grid(), points, prediction, options);
    if (Within(refined, prediction, options.max_correction_meters,
               options.max_correction_radians)) {
      consider(refined, score_of(refined));
    }
  }
  if (result.score >= options.confident_score || (options.search_linear_window_meters <= 0.0 &&
                                                  options.search_angular_window_radians <= 0.0)) {
    return result;
  }
  result.searched = true;
  const double refined_score = result.score;
  // The bar keeps a garbled scan from pulling a prediction that fits off it; when none fits
  // (the odometry slipped beyond the refinement's reach), the search is the only estimate.
  const double search_min_score = result.matched ? options.search_min_score : options.min_score;
  for (const Pose2& prediction : predictions) {
    mapping::SearchWindow window;
    window.center = prediction;
    window.linear_window_meters = options.search_linear_window_meters;
    window.angular_window_radians = options.search_angular_window_radians;
    const RelocalizationResult found =
        matcher.RelocalizeInWindow(points, window, options.min_score);
    if (!found.success) continue;
    const double score = score_of(found.pose);
    if (score >= options.search_margin_ratio * refined_score && score >= search_min_score) {
      consider(found.pose, score);
    }
  }
  return result;
}

}  // namespace semchain::localization
