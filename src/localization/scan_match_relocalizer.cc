#include "localization/scan_match_relocalizer.h"

#include <algorithm>
#include <cmath>
#include <ctime>

#include "core/angles.h"
#include "core/check.h"

namespace semchain::localization {
namespace {

double CpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace

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
  const double start = CpuSeconds();
  const mapping::CeresMatchResult refined =
      mapping::RefineWithCeres(grid_, points, match.pose, options_.ceres);
  result.cpu_seconds += CpuSeconds() - start;
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
  const std::vector<Eigen::Vector2d> points = MatchPoints(scan, laser_offset);
  return Finish(points, matcher_.MatchFullMap(points, options_.min_score));
}

RelocalizationResult ScanMatchRelocalizer::Relocalize(
    const LaserScan& scan, const Pose2& laser_offset,
    const std::vector<PoseHypothesis>& priors) const {
  SEMCHAIN_CHECK(ValidateHypotheses(priors).ok());
  const std::vector<Eigen::Vector2d> points = MatchPoints(scan, laser_offset);
  mapping::BranchAndBoundResult best;
  int best_index = -1;
  std::int64_t nodes = 0;
  int angles = 0;
  double cpu = 0.0;
  for (std::size_t i = 0; i < priors.size(); ++i) {
    const Eigen::Matrix3d& c = priors[i].covariance;
    mapping::SearchWindow window;
    window.center = priors[i].pose;
    window.linear_window_meters =
        std::clamp(3.0 * std::sqrt(std::max(c(0, 0), c(1, 1))), options_.min_linear_window_meters,
                   options_.max_linear_window_meters);
    window.angular_window_radians =
        std::clamp(3.0 * std::sqrt(c(2, 2)), options_.min_angular_window_radians, kPi);
    // Each later window must beat the best score so far (it prunes with it).
    const double min_score = std::max(options_.min_score, best.found ? best.score : 0.0);
    const mapping::BranchAndBoundResult match = matcher_.Match(points, window, min_score);
    nodes += match.nodes_scored;
    angles += match.angles;
    cpu += match.cpu_seconds;
    if (match.found && (!best.found || match.score > best.score)) {
      best = match;
      best_index = static_cast<int>(i);
    }
  }
  best.nodes_scored = nodes;
  best.angles = angles;
  best.cpu_seconds = cpu;
  RelocalizationResult result = Finish(points, best);
  result.hypothesis = best_index;
  return result;
}

}  // namespace semchain::localization
