#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "localization/scan_match_relocalizer.h"

// Scan-to-map tracking: once the robot has been found, each scan is matched against the map
// from the pose odometry predicts for it (the last tracked pose moved on by the odometry
// increment), as Cartographer's pure localization matches scans against a frozen map and as
// `semchain slam` localizes every scan in its final map. The particle filter alone tracks only
// as well as odometry and a soft likelihood field allow: nav2's σ_hit 0.2 m and 1 + Σ pz³ barely
// tell a pose 5 cm off from the right one, so between the filter's updates (every 0.25 m /
// 0.2 rad) the estimate follows the odometry, and on raw logs (MIT CSAIL's odometry turns up to
// 16° a scan, several degrees wrong) or a Neato (its /scan stamped 0.2–0.4 s late: odometry and
// laser disagree by 10–20° in turns) it trails the map by decimetres and degrees.
//
// A scan is refined from each prediction given (the odometry's; the caller may add one that
// carries on the last matched motion, for odometry that jumps) by Ceres on the scan-match
// relocalizer's match grid: Σ (1 − M)² / N plus a prior that holds the prediction where the scan
// does not constrain the pose (Cartographer's translation and rotation weights: along a wall
// or a corridor, or with the few returns of a Neato, an unweighted refinement slides by
// decimetres and turns by degrees from scan to scan); a refinement that moved its prediction
// by more than max_correction slid to another wall and is dropped. The best scoring refinement
// is taken when it scores confident_score. Otherwise (odometry that slipped or was late) a
// branch-and-bound search of a window around each prediction is refined too, and the best
// scoring of all is taken when it scores min_score (a searched pose, when a refinement fits,
// search_min_score); when none does, the scan is not matched and the caller keeps its own
// estimate.
namespace semchain::localization {

struct ScanTrackingOptions {
  // Off: the filter tracks alone (nav2's AMCL).
  bool enabled = true;
  // The scan's returns are thinned to one per this distance (the relocalizer's search thins
  // to 0.1 m for speed; a Neato's 100 returns then leave about 30 points).
  double point_spacing_meters = 0.05;
  // Scores are the mean match-grid value M of the returns at a pose (0 to 1). How well a right
  // pose scores depends on the place: MIT CSAIL's scans at the map's own poses score 0.87
  // (median; 5th percentile 0.73), Killian's and fr-clinic's first minutes about 0.4 (far and
  // cluttered returns). The thresholds are therefore relative to the typical score of the
  // recent matches (ScanTrackingThresholds), within these bounds.
  // A refinement scoring confident_ratio × typical (at most confident_score, at least min_score)
  // is taken without a search.
  double confident_score = 0.75;
  double confident_ratio = 0.9;
  // The least score of a match: min_ratio × typical, at least min_score (and at most the
  // confident score).
  double min_score = 0.15;
  double min_ratio = 0.5;
  // The typical score before the first match, and how fast it follows the matches (the weight of
  // each new match's score in its running mean).
  double initial_typical_score = 0.75;
  double typical_score_gain = 0.1;
  // The prior's weights: residuals translation_weight × (x − x̂, y − ŷ) and rotation_weight ×
  // (θ − θ̂) beside the N returns' (1 − M) / √N.
  double translation_weight = 1.0;
  double rotation_weight = 3.0;
  // A refinement that moved the prediction farther than this slid to another wall.
  double max_correction_meters = 0.15;
  double max_correction_radians = 0.1;
  // The window searched when the refinement is not confident (±, around the prediction): MIT
  // CSAIL's odometry turns up to 24° wrong in one scan.
  double search_linear_window_meters = 0.3;
  double search_angular_window_radians = 0.5;
  // A searched pose replaces a refinement of a prediction only when it scores this many times
  // more (1: whichever scores more). 1.15 kept one cluttered FR079 scan from matching 9.8° off
  // (0.49 against 0.44), but left nine Intel corridor scans 0.21 m behind (docs/experiments.md).
  double search_margin_ratio = 1.0;
  // Where a prediction's refinement fits (scores min_score), a searched pose must also score
  // search_min_ratio × typical (search_min_score, at least min_score; ScanTrackingThresholds
  // sets it). A garbled scan (a passer-by, a laser's glitch) fits some pose of a ±0.3 m,
  // ±0.5 rad window a little better than its prediction, degrees or decimetres away; a slip of
  // the odometry is told from that by a match about as good as the usual ones, or by no
  // prediction fitting at all. Without the bar (0) FR079 jumped 10.6° at a scan scoring 0.52
  // against a typical 0.86, and Intel 0.36 m along a corridor where both poses scored about 0.5
  // (docs/results.md, "Tracking on real data").
  double search_min_ratio = 0.8;
  double search_min_score = 0.0;

  // When the robot is found is the caller's decision (a lock, a pose given, a converged filter);
  // a filter counts as converged for this when its position and heading standard deviations
  // are within these (the filter's own test, 90 % of the weight within convergence_distance,
  // 0.5 m, leaves room for a match on a neighbouring wall, which the particles would follow).
  double start_max_sigma_meters = 0.1;
  double start_max_sigma_radians = 0.05;
  // Whether it also starts once global localization found the robot (a converged filter, a scan
  // matcher's lock), not only from a pose given (an initial pose, /initialpose). Off: a pose
  // found globally may be a look-alike stretch, and the filter alone can still move off it as
  // the objects and the laser tell; scan tracking holds it there (bench reloc long_corridor
  // seed 1: semantic-amcl 62.9 % and semantic-scanmatch 80.0 % with it, 77.1 % and 94.3 %
  // without).
  bool after_global_localization = false;
  // After this many scans in a row without a match it stops matching (a kidnapped robot: the
  // filter's failure detection takes over).
  int max_missed_scans = 10;

  bool Validate(std::string* error) const;
};

struct ScanTrackingResult {
  bool matched = false;
  Pose2 pose;             // the matched pose (valid when matched)
  double score = 0.0;     // its mean M (also when not matched: the best tried)
  bool searched = false;  // the window was searched (the refinement was not kept)
};

// 'options' with confident_score and min_score set for matches that typically score 'typical'.
ScanTrackingOptions ScanTrackingThresholds(const ScanTrackingOptions& options, double typical);

// Matches 'points' (the scan's returns in the robot frame, ScanMatchRelocalizer::MatchPoints
// thinned to point_spacing_meters) against the map of 'matcher' from 'predictions' (at least
// one).
ScanTrackingResult TrackScan(const ScanMatchRelocalizer& matcher,
                             const std::vector<Eigen::Vector2d>& points,
                             const std::vector<Pose2>& predictions,
                             const ScanTrackingOptions& options);

}  // namespace semchain::localization
