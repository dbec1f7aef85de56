#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

// What `semchain bench reloc` found: per method the statistics over the trials and a record of
// every trial, written as results.json and results.md.
namespace semchain::eval {

struct RelocMethodStats {
  int trials = 0;
  int successes = 0;
  double success_rate = 0.0;
  // Over successful trials.
  double mean_time_s = 0.0;  // simulated time from the start to convergence
  double mean_cpu_ms = 0.0;  // CPU time the method spent until convergence
  // Scan-matcher methods: the part of it spent searching
  // (localization::RelocTrace::search_cpu_seconds).
  double mean_search_cpu_ms = 0.0;
  double mean_iterations = 0.0;  // filter updates / matcher runs until convergence
  // Over all trials, a failed one charged for the whole time it had (up to the time limit).
  double mean_time_all_s = 0.0;
  double mean_cpu_all_ms = 0.0;
  double mean_search_cpu_all_ms = 0.0;
  double mean_error_m = 0.0;  // at the end of the trial
  double mean_error_deg = 0.0;
  // Semantic methods: error of the first pre-localization (best hypothesis), mean |x| and |y|.
  int prelocalized = 0;
  double prelocalization_error_x_m = 0.0;
  double prelocalization_error_y_m = 0.0;
  double prelocalization_error_deg = 0.0;  // mean |θ| error
  // The same against the truth carried into the map's frame (MapFrame): the relocalizer's own
  // error, without the SLAM map's.
  double prelocalization_error_map_x_m = 0.0;
  double prelocalization_error_map_y_m = 0.0;
};

// One method on one trial.
struct RelocTrialRecord {
  int trial = 0;
  double start[3] = {0.0, 0.0, 0.0};  // x, y, θ
  bool success = false;
  // Simulated time and CPU until convergence; for a failed trial, over the whole time it had
  // (the trial up to the time limit).
  double time_s = 0.0;
  double cpu_ms = 0.0;
  double search_cpu_ms = 0.0;  // the part of it spent searching (scan-matcher methods)
  // Searching over the whole trial, also after convergence (semantic-scanmatch's lock re-checks
  // go on while it tracks).
  double search_cpu_trial_ms = 0.0;
  bool localized = false;  // an estimate at the end
  double error_m = 0.0;    // at the end (when localized)
  double error_deg = 0.0;
  int prelocalizations = 0;
  int single_object_prelocalizations = 0;
  int undecided_prelocalizations = 0;
  int lock_corrections = 0;
  int lock_rechecks = 0;
  // |x|, |y| (m) and |θ| (deg) error of the first pre-localization, when there was one.
  std::optional<Eigen::Vector3d> prelocalization_error;
  // |x|, |y| (m) of it in the map's frame (RelocMethodStats::prelocalization_error_map_x_m).
  std::optional<Eigen::Vector2d> prelocalization_error_map;
};

struct RelocBenchmarkResult {
  std::string world;
  std::string live_world;
  std::string detections_source;
  int trials = 0;
  std::uint64_t seed = 0;
  int map_objects = 0;
  double map_ate_m = 0.0;  // SLAM trajectory of the mapping run against its truth
  // The trial behaviour (RelocBenchmarkOptions::trial_*).
  double trial_turns = 0.0;
  double trial_forward = 0.0;
  bool trial_face_open = false;
  double trial_turns_after = 0.0;
  std::map<std::string, RelocMethodStats> methods;
  std::map<std::string, std::vector<RelocTrialRecord>> runs;
};

std::string RelocResultsJson(const RelocBenchmarkResult& result);
std::string RelocResultsMarkdown(const RelocBenchmarkResult& result);

}  // namespace semchain::eval
