#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "core/status.h"
#include "eval/map_frame.h"
#include "eval/reloc_methods.h"
#include "io/trajectory_io.h"
#include "sim/world.h"

// `semchain bench reloc` (DESIGN.md §4, seed 000 Tables 4–5, seed 001 Fig. 13/19): the map of a
// world is built from a simulated mapping run (SLAM and semantic mapping, not the truth); the
// robot is then put at random poses in the trial region of the live world (the same world, or
// a changed one), turns in place and moves off, and every method localizes from the same
// recordings. A trial succeeds when the estimate comes within 0.25 m and 10° of the truth and
// stays there to the end of the trial, within 30 s of simulated time.
namespace semchain::eval {

struct RelocBenchmarkOptions {
  int trials = 35;
  std::uint64_t seed = 1;
  std::vector<std::string> methods = {"amcl", "semantic-amcl", "semantic-amcl-bow",
                                      "semantic-scanmatch", "scanmatch-global"};
  double success_distance = 0.25;   // metres
  double success_heading = 0.1745;  // radians (10°)
  double time_limit = 30.0;         // seconds of simulated time
  // Trial starts keep this far (metres) from any wall or object.
  double start_clearance = 0.25;
  // The trial behaviour: turns in place, then a drive of at most this far.
  double trial_turns = 2.0;
  double trial_forward = 1.0;
  // Active relocalization (off: the protocol of docs/results.md's tables): the drive goes towards
  // the most open heading, and the robot turns in place this many times where it ended
  // (sim::TrialOptions::face_most_open, rotation_after_radians).
  bool trial_face_open = false;
  double trial_turns_after = 0.0;
  // How the semantic methods use the camera (observation memory, single-object hypotheses).
  localization::LocalizerOptions method;
  // How the objects pre-localize (laser refinement of the hypotheses, look-alike margins, ...).
  localization::PreLocalizationOptions prelocalization;
  // Where the runs are made (removed afterwards); a temporary directory when empty.
  std::filesystem::path work_dir;
  // Keep the runs in work_dir (the mapping run with its map in mapping/map/, each trial's
  // recording in trial_K/), and reuse those an earlier call kept there for the same worlds,
  // seed, trial settings and detections: methods can be compared again, and a failed trial
  // replayed with `semchain localize`, without simulating anything anew.
  bool keep_runs = false;
  // Detects the objects in a run's rendered frames (the mapping run's and every trial's), e.g.
  // an ONNX detector; empty: the simulator's detection model (RUN/detections.jsonl).
  std::function<Result<std::vector<FrameDetections>>(const std::filesystem::path& run)> detect;
  // Names the source of the detections in the results ("simulator" when 'detect' is empty).
  std::string detections_source = "simulator";
};

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

// One trial as the benchmark makes it: the robot put at 'start' in 'world', turning
// options.trial_turns times and driving off up to options.trial_forward, simulated with 'seed'
// into the directory 'run'; what the methods get, and the truth at every scan.
struct RelocTrialRun {
  RelocRunInputs inputs;
  std::vector<StampedPose> truth;  // one per scan
};
Result<RelocTrialRun> SimulateRelocTrial(const sim::World& world, const Pose2& start,
                                         std::uint64_t seed, const RelocBenchmarkOptions& options,
                                         const std::filesystem::path& run);
// The same from a trial already simulated into 'run' (its log, detections, camera and truth).
Result<RelocTrialRun> LoadRelocTrial(std::uint64_t seed, const RelocBenchmarkOptions& options,
                                     const std::filesystem::path& run);

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

// 'progress' (may be empty) is called with (trials done, trials).
Result<RelocBenchmarkResult> RunRelocBenchmark(const std::filesystem::path& world,
                                               const std::filesystem::path& live_world,
                                               const RelocBenchmarkOptions& options,
                                               const std::function<void(int, int)>& progress = {});

std::string RelocResultsJson(const RelocBenchmarkResult& result);
std::string RelocResultsMarkdown(const RelocBenchmarkResult& result);

}  // namespace semchain::eval
