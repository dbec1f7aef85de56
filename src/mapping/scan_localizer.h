#pragma once

#include <string>
#include <vector>

#include "core/pose2.h"
#include "mapping/correlative_scan_matcher.h"
#include "mapping/hill_climbing_matcher.h"
#include "mapping/likelihood_field.h"
#include "mapping/occupancy_grid.h"
#include "mapping/prepared_scan.h"
#include "mapping/surface_refinement.h"

// A pose for every scan of a log after SLAM (DESIGN.md §3.2): the RBPF corrects only the scans
// it processes; the others get the odometry between their processed neighbours, with the
// neighbours' corrections interpolated in time, and are then localized in the final map by
// scan matching from there. The same routine relocalizes a scan in any map given a prior.
// Hill climbing from the interpolated pose reaches only as far as the field's kernel: where the
// odometry between two processed scans slipped (ACES scan 3720 at t = 789 s: 11° in a turn in
// place), the scan stays in a local optimum scoring a third of its neighbours', the trajectory
// holds a pose the map disagrees with, and the map is drawn with that scan turned. Such scans
// have their heading swept and take the sweep's fit when it is clearly better.
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
  // The refinement's prior: the interpolated pose with these standard deviations (metres,
  // radians; 0: no prior). Along a corridor the scan says little, and a map drawn from two
  // passes says it twice: without the prior ACES's scans jittered ±0.1 m along a corridor at
  // t = 220 s, and bench track's worst scan was 0.69 m from them (0.33 m with it).
  double prior_sigma_meters = 0.05;
  double prior_sigma_radians = 0.05;
  // A scan whose match finds fewer endpoints on obstacles (or than a third of its returns, when
  // that is fewer: RequiredMatches) keeps its interpolated pose.
  int min_matched_points = 50;
  double match_max_range_meters = 30.0;
  int match_beam_step = 2;  // hill climbing uses every n-th return (the refinement all)
  // A scan whose localized pose scores (the field's mean score per return) below this fraction
  // of the typical score of its neighbours — the median over the matched scans among the
  // 'typical_window_scans' either side — is searched over 'search' around its interpolated pose,
  // and so is one left unmatched beside matched neighbours; 0 searches none. 0.9, with a ±0.3 m
  // window, also searched runs of corridor scans whose interpolated times are muddled (Intel's
  // restamped bursts) and moved them 0.2–0.5 m along the corridor (docs/experiments.md).
  double search_below_ratio = 0.7;
  int typical_window_scans = 25;
  // Odometry slips in heading between two processed scans (a turn in place); in translation it is
  // good to centimetres there, so the search sweeps the heading only and hill climbing then
  // finds the translation. Searched ±0.1 m in x and y too, two of a Neato's scans of 30 returns
  // moved 0.16 and 0.25 m onto walls they had not seen.
  CorrelativeSearchOptions search{0.0,  0.25, 0.05,
                                  0.01, 2,    HillClimbingOptions{0.025, 0.01, 6, 300}};
  // The searched pose replaces the local match only when it scores this many times as much
  // (along a corridor or a row of doors the window holds other fits scoring about as well, and
  // there the interpolated pose is the better guide) and at least search_below_ratio of the
  // neighbours' typical score.
  double search_margin_ratio = 1.1;

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
  double score = 0.0;  // the field's mean score per return at 'pose' (when matched)
};

// Scan-matches 'scan' against 'field' starting from 'prior'; keeps the prior when the match
// finds fewer than RequiredMatches(min_matched_points, returns) endpoints on obstacles.
LocalizationResult LocalizeScan(const LikelihoodField& field, const PreparedScan& scan,
                                const Pose2& prior, const EveryScanOptions& options);

struct EveryScanStatistics {
  int matched = 0;   // scans refined by scan matching (the others keep their prior)
  int searched = 0;  // scans scoring below search_below_ratio of their neighbours, or unmatched
  int replaced = 0;  // searched scans whose searched pose was taken
};

// Localizes every scan in 'field' from (*poses)[i] (LocalizeScan) and writes the result back;
// then searches the scans that score below search_below_ratio of their neighbours. 'threads'
// as ParallelFor; the result does not depend on them.
EveryScanStatistics LocalizeScans(const LikelihoodField& field,
                                  const std::vector<PreparedScan>& scans, std::vector<Pose2>* poses,
                                  const EveryScanOptions& options, int threads);

}  // namespace semchain::mapping
