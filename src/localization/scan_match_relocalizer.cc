#include "localization/scan_match_relocalizer.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"
#include "core/check.h"
#include "core/cpu_time.h"

namespace semchain::localization {

bool ScanMatchRelocalizerOptions::Validate(std::string* error) const {
  if (!grid.Validate(error) || !branch_and_bound.Validate(error) || !ceres.Validate(error)) {
    return false;
  }
  if (!(min_score >= 0.0 && min_score <= 1.0)) {
    *error = "min_score must be in [0, 1]";
    return false;
  }
  if (!(max_range_meters > 0.0 && min_point_spacing_meters >= 0.0)) {
    *error = "max_range_meters must be > 0 and min_point_spacing_meters >= 0";
    return false;
  }
  if (!(min_linear_window_meters > 0.0 && max_linear_window_meters >= min_linear_window_meters &&
        min_angular_window_radians > 0.0)) {
    *error = "search window limits must be positive and ordered";
    return false;
  }
  if (!(narrow_linear_window_meters >= 0.0 && narrow_angular_window_radians > 0.0)) {
    *error = "narrow_linear_window_meters must be >= 0 and narrow_angular_window_radians > 0";
    return false;
  }
  return true;
}

ScanMatchRelocalizer::ScanMatchRelocalizer(const mapping::MapImage& map,
                                           const ScanMatchRelocalizerOptions& options)
    : options_(options),
      grid_(mapping::MakeMatchGrid(map, options.grid)),
      matcher_(grid_, options.branch_and_bound) {
  std::string error;
  SEMCHAIN_CHECK(options_.Validate(&error));
}

std::vector<Eigen::Vector2d> ScanMatchRelocalizer::MatchPoints(const LaserScan& scan,
                                                               const Pose2& laser_offset) const {
  std::vector<Eigen::Vector2d> points;
  const double spacing_squared =
      options_.min_point_spacing_meters * options_.min_point_spacing_meters;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    if (!scan.IsReturn(i) || scan.ranges[i] > options_.max_range_meters) continue;
    const double a = scan.BeamAngle(i);
    const Eigen::Vector2d p =
        laser_offset * Eigen::Vector2d(scan.ranges[i] * std::cos(a), scan.ranges[i] * std::sin(a));
    if (!points.empty() && (p - points.back()).squaredNorm() < spacing_squared) continue;
    points.push_back(p);
  }
  return points;
}

RelocalizationResult ScanMatchRelocalizer::Finish(
    const std::vector<Eigen::Vector2d>& points, const mapping::BranchAndBoundResult& match) const {
  RelocalizationResult result;
  result.points = static_cast<int>(points.size());
  result.nodes_scored = match.nodes_scored;
  result.angles = match.angles;
  result.score = match.score;
  result.cpu_seconds = match.cpu_seconds;
  if (!match.found) return result;
  const double start = ProcessCpuSeconds();
  const mapping::CeresMatchResult refined =
      mapping::RefineWithCeres(grid_, points, match.pose, options_.ceres);
  result.cpu_seconds += ProcessCpuSeconds() - start;
  result.success = true;
  result.coarse_pose = match.pose;
  result.pose = refined.pose;
  result.refined_score = refined.score;
  return result;
}

RelocalizationResult ScanMatchRelocalizer::RelocalizeInWindow(
    const LaserScan& scan, const Pose2& laser_offset, const mapping::SearchWindow& window) const {
  const std::vector<Eigen::Vector2d> points = MatchPoints(scan, laser_offset);
  return Finish(points, matcher_.Match(points, window, options_.min_score));
}

RelocalizationResult ScanMatchRelocalizer::RelocalizeGlobal(const LaserScan& scan,
                                                            const Pose2& laser_offset) const {
  return RelocalizeGlobal(MatchPoints(scan, laser_offset));
}

RelocalizationResult ScanMatchRelocalizer::RelocalizeGlobal(
    const std::vector<Eigen::Vector2d>& points) const {
  return Finish(points, matcher_.MatchFullMap(points, options_.min_score));
}

mapping::SearchWindow ScanMatchRelocalizer::WindowOf(const PoseHypothesis& prior,
                                                     WindowWidth width) const {
  mapping::SearchWindow window;
  window.center = prior.pose;
  const Eigen::Matrix3d& c = prior.covariance;
  window.linear_window_meters =
      width.wide_linear
          ? std::clamp(3.0 * std::sqrt(std::max(c(0, 0), c(1, 1))),
                       options_.min_linear_window_meters, options_.max_linear_window_meters)
          : options_.narrow_linear_window_meters;
  window.angular_window_radians =
      width.wide_angular
          ? std::clamp(3.0 * std::sqrt(c(2, 2)), options_.min_angular_window_radians, kPi)
          : options_.narrow_angular_window_radians;
  return window;
}

void ScanMatchRelocalizer::SearchPriors(const std::vector<Eigen::Vector2d>& points,
                                        const std::vector<PoseHypothesis>& priors,
                                        WindowWidth width, PriorSearch* search) const {
  for (std::size_t i = 0; i < priors.size(); ++i) {
    const double bound =
        std::max(options_.min_score, search->best.found ? search->best.score : 0.0);
    const mapping::BranchAndBoundResult match =
        matcher_.Match(points, WindowOf(priors[i], width), bound);
    search->nodes_scored += match.nodes_scored;
    search->angles += match.angles;
    search->cpu_seconds += match.cpu_seconds;
    if (match.found && (!search->best.found || match.score > search->best.score)) {
      search->best = match;
      search->hypothesis = static_cast<int>(i);
    }
  }
}

RelocalizationResult ScanMatchRelocalizer::Relocalize(
    const LaserScan& scan, const Pose2& laser_offset,
    const std::vector<PoseHypothesis>& priors) const {
  return Relocalize(MatchPoints(scan, laser_offset), priors);
}

RelocalizationResult ScanMatchRelocalizer::Relocalize(
    const std::vector<Eigen::Vector2d>& points, const std::vector<PoseHypothesis>& priors) const {
  SEMCHAIN_CHECK(ValidateHypotheses(priors).ok());
  const bool narrow_first = options_.narrow_linear_window_meters > 0.0;
  WindowWidth width{!narrow_first, !narrow_first};
  PriorSearch search;
  SearchPriors(points, priors, width, &search);
  // Widen where the best match may be cut off by the border (everywhere when nothing matched).
  // The best match's border flags are of the window it was found in; a wider search that finds
  // nothing better leaves it inside the wider window.
  while (true) {
    const WindowWidth wider{
        width.wide_linear || !search.best.found || search.best.on_linear_edge,
        width.wide_angular || !search.best.found || search.best.on_angular_edge};
    if (wider.wide_linear == width.wide_linear && wider.wide_angular == width.wide_angular) break;
    width = wider;
    SearchPriors(points, priors, width, &search);
  }
  mapping::BranchAndBoundResult best = search.best;
  best.nodes_scored = search.nodes_scored;
  best.angles = search.angles;
  best.cpu_seconds = search.cpu_seconds;
  RelocalizationResult result = Finish(points, best);
  result.hypothesis = search.hypothesis;
  result.widened_linear = narrow_first && width.wide_linear;
  result.widened_angular = narrow_first && width.wide_angular;
  return result;
}

}  // namespace semchain::localization
