#include "mapping/scan_localizer.h"

#include <algorithm>

#include "core/check.h"
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

LocalizationResult LocalizeScan(const LikelihoodField& field, const PreparedScan& scan,
                                const Pose2& prior, const EveryScanOptions& options) {
  // Hill climbing on every n-th return, the refinement on all of them.
  const MatchPoints sparse =
      SelectMatchPoints(scan, options.match_max_range_meters, options.match_beam_step);
  const MatchResult match = HillClimb(field, sparse, prior, options.matcher);
  const int available = sparse.measured * options.match_beam_step;
  if (match.evaluation.matched * options.match_beam_step <
      RequiredMatches(options.min_matched_points, available)) {
    return {prior, false};
  }
  if (!options.refinement.enabled) return {match.pose, true};
  const MatchPoints points = SelectMatchPoints(scan, options.match_max_range_meters);
  return {RefineOnSurface(field, points, match.pose, options.refinement).pose, true};
}

}  // namespace semchain::mapping
