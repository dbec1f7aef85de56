#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/status.h"
#include "eval/ate.h"
#include "io/trajectory_io.h"

// Relative pose error over stretches of travel (the drift measure of the KITTI odometry
// benchmark, Geiger et al. CVPR 2012, in the plane): for every pose, the estimate's motion to the
// first pose at least L metres further along the true path, against the truth's. It says how
// far a trajectory drifts between loop closures, which an aligned ATE mixes with where the
// closures are.
namespace semchain::eval {

struct RpeOptions {
  // Stretch lengths, metres of travel along the true path (each > 0).
  std::vector<double> travel_meters = {10.0, 50.0};
  // How estimate and truth poses are paired (its 'align' is ignored: relative motions need none).
  AteOptions pairing;
};

// The errors of all stretches of one length.
struct RpeStretches {
  double travel_m = 0.0;
  std::size_t stretches = 0;  // 0 when the true path is shorter than travel_m
  // |translation| of the error motion (truth⁻¹ · estimate, both relative), metres.
  double translation_median_m = 0.0;
  double translation_p95_m = 0.0;
  double translation_max_m = 0.0;
  // |rotation| of the error motion, degrees.
  double rotation_median_deg = 0.0;
  double rotation_p95_deg = 0.0;
  double rotation_max_deg = 0.0;
  // Median of (estimated − true) length of the stretch measured along the true direction:
  // negative when the estimate is shorter than the truth (a scale error).
  double along_track_median_m = 0.0;
};

struct RpeResult {
  std::size_t poses = 0;                // in the estimate
  std::size_t matched = 0;              // with a truth pose
  std::vector<RpeStretches> stretches;  // one per travel_meters entry, in its order
};

// Fails when the travel lengths are not all positive or the poses cannot be paired (EvaluateAte).
Result<RpeResult> EvaluateRpe(const std::vector<StampedPose>& estimate,
                              const std::vector<StampedPose>& truth,
                              const RpeOptions& options = {});

// The JSON object `semchain eval rpe` prints.
std::string RpeResultToJson(const RpeResult& result);

}  // namespace semchain::eval
