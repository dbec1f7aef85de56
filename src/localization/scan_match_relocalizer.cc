#include "localization/scan_match_relocalizer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "core/angles.h"
#include "core/check.h"
#include "core/cpu_time.h"
#include "mapping/distance_field.h"

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

namespace {

// The map's free cells dilated by 'margin' metres, as a mask of the map's cells.
std::vector<std::uint8_t> FreeSpaceMask(const mapping::MapImage& map, double margin) {
  cv::Mat mask = mapping::MapCellMask(map, mapping::CellState::kFree);
  const int radius = static_cast<int>(std::ceil(margin / map.resolution));
  if (radius > 0) {
    cv::dilate(
        mask, mask,
        cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * radius + 1, 2 * radius + 1)));
  }
  return std::vector<std::uint8_t>(mask.begin<std::uint8_t>(), mask.end<std::uint8_t>());
}

}  // namespace

ScanMatchRelocalizer::ScanMatchRelocalizer(const mapping::MapImage& map,
                                           const ScanMatchRelocalizerOptions& options)
    : options_(options),
      grid_(mapping::MakeMatchGrid(map, options.grid)),
      matcher_(grid_, options.branch_and_bound) {
  std::string error;
  SEMCHAIN_CHECK(options_.Validate(&error));
  if (options_.global_free_space_margin_meters >= 0.0) {
    SEMCHAIN_CHECK(grid_.width == map.width && grid_.height == map.height);
    free_space_.emplace(FreeSpaceMask(map, options_.global_free_space_margin_meters), map.width,
                        map.height, options_.branch_and_bound.branch_and_bound_depth);
  }
}

std::vector<Eigen::Vector2d> ScanMatchRelocalizer::MatchPoints(const LaserScan& scan,
                                                               const Pose2& laser_offset) const {
  return MatchPoints(scan, laser_offset, options_.min_point_spacing_meters);
}

std::vector<Eigen::Vector2d> ScanMatchRelocalizer::MatchPoints(const LaserScan& scan,
                                                               const Pose2& laser_offset,
                                                               double min_spacing_meters) const {
  std::vector<Eigen::Vector2d> points;
  const double spacing_squared = min_spacing_meters * min_spacing_meters;
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
  result.root_nodes = match.root_nodes;
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
  return result;
}

Pose2 ScanMatchRelocalizer::Refine(const std::vector<Eigen::Vector2d>& points,
                                   const Pose2& initial) const {
  return mapping::RefineWithCeres(grid_, points, initial, options_.ceres).pose;
}

RelocalizationResult ScanMatchRelocalizer::RelocalizeInWindow(
    const LaserScan& scan, const Pose2& laser_offset, const mapping::SearchWindow& window) const {
  return RelocalizeInWindow(MatchPoints(scan, laser_offset), window);
}

RelocalizationResult ScanMatchRelocalizer::RelocalizeInWindow(
    const std::vector<Eigen::Vector2d>& points, const mapping::SearchWindow& window) const {
  return RelocalizeInWindow(points, window, options_.min_score);
}

RelocalizationResult ScanMatchRelocalizer::RelocalizeInWindow(
    const std::vector<Eigen::Vector2d>& points, const mapping::SearchWindow& window,
    double min_score) const {
  return Finish(points, matcher_.Match(points, window, min_score));
}

RelocalizationResult ScanMatchRelocalizer::RelocalizeGlobal(const LaserScan& scan,
                                                            const Pose2& laser_offset) const {
  return RelocalizeGlobal(MatchPoints(scan, laser_offset));
}

RelocalizationResult ScanMatchRelocalizer::RelocalizeGlobal(
    const std::vector<Eigen::Vector2d>& points) const {
  return Finish(points, matcher_.MatchFullMap(points, options_.min_score,
                                              free_space_ ? &*free_space_ : nullptr));
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
  window.angular_window_radians = std::min(
      WideAngularWindow(prior), width.angular_scale * options_.narrow_angular_window_radians);
  return window;
}

double ScanMatchRelocalizer::WideAngularWindow(const PoseHypothesis& prior) const {
  return std::clamp(3.0 * std::sqrt(prior.covariance(2, 2)), options_.min_angular_window_radians,
                    kPi);
}

bool ScanMatchRelocalizer::SearchPriors(const std::vector<Eigen::Vector2d>& points,
                                        const std::vector<PoseHypothesis>& priors,
                                        WindowWidth width, const WindowWidth* searched,
                                        PriorSearch* search) const {
  bool improved = false;
  for (std::size_t i = 0; i < priors.size(); ++i) {
    const double bound =
        std::max(options_.min_score, search->best.found ? search->best.score : 0.0);
    mapping::SearchWindow window = WindowOf(priors[i], width);
    if (searched != nullptr) {
      window.searched_angular_window_radians =
          WindowOf(priors[i], *searched).angular_window_radians;
    }
    const mapping::BranchAndBoundResult match = matcher_.Match(points, window, bound);
    search->nodes_scored += match.nodes_scored;
    search->angles += match.angles;
    search->cpu_seconds += match.cpu_seconds;
    if (match.found && (!search->best.found || match.score > search->best.score)) {
      search->best = match;
      search->hypothesis = static_cast<int>(i);
      improved = true;
    }
  }
  return improved;
}

RelocalizationResult ScanMatchRelocalizer::Relocalize(
    const LaserScan& scan, const Pose2& laser_offset,
    const std::vector<PoseHypothesis>& priors) const {
  return Relocalize(MatchPoints(scan, laser_offset), priors);
}

RelocalizationResult ScanMatchRelocalizer::Relocalize(
    const std::vector<Eigen::Vector2d>& points, const std::vector<PoseHypothesis>& priors) const {
  SEMCHAIN_CHECK(ValidateHypotheses(priors).ok());
  constexpr double kWide = std::numeric_limits<double>::infinity();
  const bool narrow_first = options_.narrow_linear_window_meters > 0.0;
  WindowWidth width{!narrow_first, narrow_first ? 1.0 : kWide};
  double widest_angular = 0.0;  // the wide headings of the widest prior
  for (const PoseHypothesis& prior : priors) {
    widest_angular = std::max(widest_angular, WideAngularWindow(prior));
  }
  const auto angular_wide = [&](const WindowWidth& w) {
    return w.angular_scale * options_.narrow_angular_window_radians >= widest_angular;
  };
  PriorSearch search;
  SearchPriors(points, priors, width, nullptr, &search);
  // Widen where the best match may be cut off by the border (everywhere when nothing matched).
  // The best match's border flags are of the window it was found in; a wider search that finds
  // nothing better leaves it inside the wider window in the widened dimension.
  while (true) {
    const bool found = search.best.found;
    const bool widen_linear = !width.wide_linear && (!found || search.best.on_linear_edge);
    const bool widen_angular = !angular_wide(width) && (!found || search.best.on_angular_edge);
    if (!widen_linear && !widen_angular) break;
    WindowWidth wider = width;
    if (!found) {
      wider = {true, kWide};
    } else {
      if (widen_linear) wider.wide_linear = true;
      if (widen_angular) wider.angular_scale *= 2.0;
    }
    const bool improved =
        SearchPriors(points, priors, wider, widen_linear || !found ? nullptr : &width, &search);
    if (found && !improved) {
      if (widen_linear) search.best.on_linear_edge = false;
      if (widen_angular) search.best.on_angular_edge = false;
    }
    width = wider;
  }
  mapping::BranchAndBoundResult best = search.best;
  best.nodes_scored = search.nodes_scored;
  best.angles = search.angles;
  best.cpu_seconds = search.cpu_seconds;
  RelocalizationResult result = Finish(points, best);
  result.hypothesis = search.hypothesis;
  result.widened_linear = narrow_first && width.wide_linear;
  result.widened_angular = narrow_first && width.angular_scale > 1.0;
  return result;
}

}  // namespace semchain::localization
