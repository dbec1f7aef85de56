#include "mapping/scan_localizer.h"

#include <algorithm>

#include "core/check.h"
#include "mapping/parallel_for.h"
#include "mapping/required_matches.h"

namespace semchain::mapping {

bool EveryScanOptions::Validate(std::string* error) const {
  if (method != "localize" && method != "interpolate") {
    *error = "method must be 'localize' or 'interpolate', not '" + method + "'";
    return false;
  }
  if (refinement_passes < 0 || min_matched_points < 0 || !(match_max_range_meters > 0.0) ||
      match_beam_step < 1) {
    *error = "refinement_passes and min_matched_points must be >= 0, match_max_range_meters > 0";
    return false;
  }
  if (!(search_below_ratio >= 0.0) || typical_window_scans < 1 || !(search_margin_ratio >= 1.0)) {
    *error = "search_below_ratio must be >= 0, typical_window_scans >= 1, search_margin_ratio >= 1";
    return false;
  }
  if (!search.Validate(error)) {
    *error = "search: " + *error;
    return false;
  }
  return matcher.Validate(error) && refinement.Validate(error);
}

std::vector<Pose2> InterpolateTrajectory(const std::vector<Pose2>& odometry,
                                         const std::vector<double>& timestamps,
                                         const std::vector<std::pair<int, Pose2>>& processed) {
  SEMCHAIN_CHECK(odometry.size() == timestamps.size() && !processed.empty());
  // Dead reckoning from the corrected pose of processed scan k to scan i.
  auto from = [&](std::size_t k, std::size_t i) {
    const auto& [index, pose] = processed[k];
    return pose * odometry[static_cast<std::size_t>(index)].Between(odometry[i]);
  };
  std::vector<Pose2> poses(odometry.size());
  std::size_t next = 0;  // first processed scan with index >= i
  for (std::size_t i = 0; i < odometry.size(); ++i) {
    while (next < processed.size() && processed[next].first < static_cast<int>(i)) ++next;
    if (next == 0) {
      poses[i] = from(0, i);
    } else if (next == processed.size()) {
      poses[i] = from(processed.size() - 1, i);
    } else {
      const double t0 = timestamps[static_cast<std::size_t>(processed[next - 1].first)];
      const double t1 = timestamps[static_cast<std::size_t>(processed[next].first)];
      const double t = t1 > t0 ? std::clamp((timestamps[i] - t0) / (t1 - t0), 0.0, 1.0) : 1.0;
      poses[i] = Interpolate(from(next - 1, i), from(next, i), t);
    }
  }
  return poses;
}

namespace {

double MeanScore(const LikelihoodField& field, const MatchPoints& points, const Pose2& pose) {
  if (points.size() == 0) return 0.0;
  return field.Evaluate(points, pose).score / static_cast<double>(points.size());
}

// The pose 'match_pose' (found on 'sparse', every match_beam_step-th return, of which
// 'sparse_matched' lie on obstacles there) refined on all returns when the refinement is on;
// not matched when too few returns lie on obstacles.
LocalizationResult Finish(const LikelihoodField& field, const PreparedScan& scan,
                          const MatchPoints& sparse, const Pose2& match_pose, int sparse_matched,
                          const Pose2& prior, const EveryScanOptions& options) {
  const int available = sparse.measured * options.match_beam_step;
  if (sparse_matched * options.match_beam_step <
      RequiredMatches(options.min_matched_points, available)) {
    return {prior, false, 0.0};
  }
  const MatchPoints points = SelectMatchPoints(scan, options.match_max_range_meters);
  PosePrior held{prior, Eigen::Vector3d(options.prior_sigma_meters, options.prior_sigma_meters,
                                        options.prior_sigma_radians)};
  const bool with_prior = options.prior_sigma_meters > 0.0 && options.prior_sigma_radians > 0.0;
  const Pose2 pose = options.refinement.enabled
                         ? RefineOnSurface(field, points, match_pose, options.refinement,
                                           with_prior ? &held : nullptr)
                               .pose
                         : match_pose;
  return {pose, true, MeanScore(field, points, pose)};
}

// The median score of the matched scans within 'window' of scan i (i itself left out); 0 when
// none is matched.
double TypicalScore(const std::vector<LocalizationResult>& results, int i, int window) {
  std::vector<double> scores;
  const int count = static_cast<int>(results.size());
  for (int j = std::max(0, i - window); j <= std::min(count - 1, i + window); ++j) {
    if (j != i && results[static_cast<std::size_t>(j)].matched) {
      scores.push_back(results[static_cast<std::size_t>(j)].score);
    }
  }
  if (scores.empty()) return 0.0;
  const auto middle = scores.begin() + static_cast<std::ptrdiff_t>(scores.size() / 2);
  std::nth_element(scores.begin(), middle, scores.end());
  return *middle;
}

}  // namespace

LocalizationResult LocalizeScan(const LikelihoodField& field, const PreparedScan& scan,
                                const Pose2& prior, const EveryScanOptions& options) {
  // Hill climbing on every n-th return, the refinement on all of them.
  const MatchPoints sparse =
      SelectMatchPoints(scan, options.match_max_range_meters, options.match_beam_step);
  const MatchResult match = HillClimb(field, sparse, prior, options.matcher);
  return Finish(field, scan, sparse, match.pose, match.evaluation.matched, prior, options);
}

EveryScanStatistics LocalizeScans(const LikelihoodField& field,
                                  const std::vector<PreparedScan>& scans, std::vector<Pose2>* poses,
                                  const EveryScanOptions& options, int threads) {
  SEMCHAIN_CHECK(poses->size() == scans.size());
  const std::vector<Pose2> priors = *poses;
  std::vector<LocalizationResult> results(scans.size());
  const int count = static_cast<int>(scans.size());
  ParallelFor(count, threads, [&](int i) {
    const auto k = static_cast<std::size_t>(i);
    results[k] = LocalizeScan(field, scans[k], priors[k], options);
  });
  // Scores are compared with the neighbours' before any is replaced, so the order of the
  // threads does not matter.
  std::vector<int> flagged;
  std::vector<double> bars;  // search_below_ratio of each flagged scan's typical score
  if (options.search_below_ratio > 0.0) {
    for (int i = 0; i < count; ++i) {
      // A scan left unmatched (too few returns on obstacles where hill climbing ended) scores 0.
      const LocalizationResult& result = results[static_cast<std::size_t>(i)];
      const double bar =
          options.search_below_ratio * TypicalScore(results, i, options.typical_window_scans);
      if (bar > 0.0 && result.score < bar) {
        flagged.push_back(i);
        bars.push_back(bar);
      }
    }
  }
  std::vector<LocalizationResult> searched(flagged.size());
  ParallelFor(static_cast<int>(flagged.size()), threads, [&](int f) {
    const auto k = static_cast<std::size_t>(flagged[static_cast<std::size_t>(f)]);
    const MatchResult found = CorrelativeSearch(field, scans[k], priors[k], options.search,
                                                options.match_max_range_meters);
    // The search's evaluation is on all returns; the matched test counts the sparse ones.
    const MatchPoints sparse =
        SelectMatchPoints(scans[k], options.match_max_range_meters, options.match_beam_step);
    searched[static_cast<std::size_t>(f)] =
        Finish(field, scans[k], sparse, found.pose, field.Evaluate(sparse, found.pose).matched,
               priors[k], options);
  });
  EveryScanStatistics statistics;
  statistics.searched = static_cast<int>(flagged.size());
  for (std::size_t f = 0; f < flagged.size(); ++f) {
    // The searched pose must also fit as its neighbours do: a scan of a place the map holds
    // little of (a Neato's 30 returns on a wall only it saw) scores low at its right pose, and
    // the best of a window there is a wrong pose scoring a little more.
    LocalizationResult& result = results[static_cast<std::size_t>(flagged[f])];
    if (searched[f].matched && searched[f].score > options.search_margin_ratio * result.score &&
        searched[f].score >= bars[f]) {
      result = searched[f];
      ++statistics.replaced;
    }
  }
  for (std::size_t k = 0; k < scans.size(); ++k) {
    (*poses)[k] = results[k].pose;
    if (results[k].matched) ++statistics.matched;
  }
  return statistics;
}

}  // namespace semchain::mapping
