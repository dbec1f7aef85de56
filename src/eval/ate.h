#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "core/status.h"
#include "io/trajectory_io.h"

// Absolute trajectory error (Sturm et al., "A benchmark for the evaluation of RGB-D SLAM
// systems", IROS 2012, §V-B) of an estimated trajectory against the truth, in the plane.
namespace semchain::eval {

struct AteOptions {
  // An estimate pose takes the truth pose nearest in time when within this many seconds...
  double timestamp_tolerance_s = 1e-3;
  // ...otherwise the truth interpolated between its two poses around that time, when they are
  // at most this far apart; an estimate pose in a larger gap or outside the truth is unmatched.
  double max_interpolation_gap_s = 0.5;
  // Our simulated maps are in world coordinates (DESIGN.md §3.1), so by default no alignment.
  // When true, the estimate is first moved by the SE(2) transform that best fits its positions
  // to the truth's in the least-squares sense (Umeyama 1991 / Horn 1987, without scale).
  bool align = false;
  // true: the i-th estimate pose is scored against the i-th truth pose (both sequences the same
  // length), timestamps ignored — for estimates made scan by scan from a log whose timestamps
  // cannot pair them (the corrected Killian and FR-campus logs stamp nearly every scan alike).
  bool pair_by_index = false;
};

struct AteResult {
  std::size_t poses = 0;    // poses in the estimate
  std::size_t matched = 0;  // estimate poses with a truth pose
  double ate_rmse_m = 0.0;  // root mean square of the position errors
  double ate_mean_m = 0.0;
  double ate_max_m = 0.0;
  double rot_rmse_deg = 0.0;  // root mean square of the heading errors
  Pose2 alignment;            // applied to the estimate (identity without 'align')
};

// The SE(2) transform T minimising Σ |T ⊕ from_i - to_i|² over point pairs (closed form: the
// rotation angle is atan2 of the summed cross and dot products of the centred points).
// 'from' and 'to' have the same size (at least 1).
Pose2 FitRigidTransform2D(const std::vector<Pose2>& from, const std::vector<Pose2>& to);

// The estimate's poses and the truth's at the same times (or indices), as AteOptions pairs them.
struct PairedPoses {
  std::vector<Pose2> estimated;
  std::vector<Pose2> reference;
};
// Fails as EvaluateAte does (no pose matches, lengths differ by index, truth timestamps shared).
Result<PairedPoses> PairWithTruth(const std::vector<StampedPose>& estimate,
                                  const std::vector<StampedPose>& truth, const AteOptions& options);

// Scores 'estimate' against 'truth' (both in any order, unless paired by index). Fails when no
// pose matches, when paired by index and the lengths differ, and when pairing by time and two
// truth poses share a timestamp (the pairing would be arbitrary).
Result<AteResult> EvaluateAte(const std::vector<StampedPose>& estimate,
                              const std::vector<StampedPose>& truth,
                              const AteOptions& options = {});

// The JSON object `semchain eval ate` prints (keys as in DESIGN.md §4).
std::string AteResultToJson(const AteResult& result);

}  // namespace semchain::eval
