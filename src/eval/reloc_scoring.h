#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/pose2.h"
#include "eval/map_frame.h"
#include "eval/reloc_benchmark_options.h"
#include "eval/reloc_results.h"
#include "io/trajectory_io.h"
#include "localization/reloc_trace.h"

// How `semchain bench reloc` scores a method's run of one trial against the truth, and how the
// scores add up to the method's statistics.
namespace semchain::eval {

// How one method did on one trial.
struct RelocTrialOutcome {
  // The estimate came within the tolerance within the time limit and stayed there to the end.
  bool success = false;
  bool localized = false;  // an estimate at the end, and its error
  double final_error_m = 0.0;
  double final_error_rad = 0.0;
  // Simulated time (s), CPU (s) and search CPU (s) until convergence; for a failed trial, what
  // the method spent over the whole time it had (the trial up to the time limit).
  double time = 0.0;
  double cpu = 0.0;
  double search_cpu = 0.0;
  int iterations = 0;    // until convergence (successful trials)
  double error_m = 0.0;  // at the end (successful trials)
  double error_rad = 0.0;
  bool prelocalized = false;  // the first pre-localization's |x|, |y| and |θ| error
  Eigen::Vector2d prelocalization_error = Eigen::Vector2d::Zero();
  double prelocalization_error_rad = 0.0;
  Eigen::Vector2d prelocalization_error_map = Eigen::Vector2d::Zero();  // with a map frame
};

// Scores 'trace' against 'truth' (one pose per scan) with the options' tolerances and limit;
// with 'map_frame' (may be null) also the pre-localization against the truth in the map's frame.
RelocTrialOutcome ScoreRelocTrace(const localization::RelocTrace& trace,
                                  const std::vector<StampedPose>& truth,
                                  const RelocBenchmarkOptions& options,
                                  const MapFrame* map_frame = nullptr);

// Adds one trial's outcome to a method's sums; FinishRelocStats turns the sums into means.
void AccumulateRelocOutcome(const RelocTrialOutcome& outcome, RelocMethodStats* stats);
void FinishRelocStats(RelocMethodStats* stats);

// The record of trial 'trial' started at 'start': what 'trace' counted and how it scored.
RelocTrialRecord RelocTrialRecordOf(int trial, const Pose2& start,
                                    const localization::RelocTrace& trace,
                                    const RelocTrialOutcome& outcome);

}  // namespace semchain::eval
