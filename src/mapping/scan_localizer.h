#pragma once

#include <string>
#include <vector>

#include "core/pose2.h"
#include "mapping/hill_climbing_matcher.h"
#include "mapping/likelihood_field.h"
#include "mapping/occupancy_grid.h"
#include "mapping/prepared_scan.h"
#include "mapping/surface_refinement.h"

// A pose for every scan of a log after SLAM (DESIGN.md §3.2): the RBPF corrects only the scans
// it processes; the others get the odometry between their processed neighbours, with the
// neighbours' corrections interpolated in time, and are then localized in the final map by
// scan matching from there. The same routine relocalizes a scan in any map given a prior.
namespace semchain::mapping {

struct EveryScanOptions {
  // "localize": interpolate, then scan-match each scan in the final map (default);
  // "interpolate": the interpolated odometry only.
  std::string method = "localize";
  // After localizing, rebuild the map from every localized scan and localize again this many
  // times (a denser map, sharper obstacle means).
  int refinement_passes = 0;
  HillClimbingOptions matcher{0.02, 0.02, 7, 400};
  // Gauss-Newton point-to-surface refinement after hill climbing.
  SurfaceRefinementOptions refinement;
  // A scan whose match finds fewer endpoints on obstacles (or than a third of its returns, when
  // that is fewer: RequiredMatches) keeps its interpolated pose.
  int min_matched_points = 50;
  double match_max_range_meters = 30.0;
  int match_beam_step = 2;  // hill climbing uses every n-th return (the refinement all)

  bool Validate(std::string* error) const;
};

// Odometry increments of every scan re-anchored on the corrected poses of the processed ones:
// between processed scans k and k+1, pose_i blends (linearly in time) the dead reckoning
// x_k ⊕ (odometry_k⁻¹ ⊕ odometry_i) forward from k and the same backward from k+1; before the
// first and after the last processed scan, dead reckoning from it. Blending the two local
// predictions, not the global corrections x_k ⊕ odometry_k⁻¹, keeps the result independent of
// where the odometry frame lies: a correction's rotation acts about the odometry origin, and
// interpolating two of them 576 m from it (mit-csail) put the scans between metres off.
// 'processed' holds (scan index, corrected pose) in increasing index order.
std::vector<Pose2> InterpolateTrajectory(const std::vector<Pose2>& odometry,
                                         const std::vector<double>& timestamps,
                                         const std::vector<std::pair<int, Pose2>>& processed);

struct LocalizationResult {
  Pose2 pose;
  bool matched = false;
};

// Scan-matches 'scan' against 'field' starting from 'prior'; keeps the prior when the match
// finds fewer than RequiredMatches(min_matched_points, returns) endpoints on obstacles.
LocalizationResult LocalizeScan(const LikelihoodField& field, const PreparedScan& scan,
                                const Pose2& prior, const EveryScanOptions& options);

}  // namespace semchain::mapping
