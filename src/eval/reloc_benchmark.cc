#include "eval/reloc_benchmark.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "eval/map_frame.h"
#include "eval/reloc_mapping_run.h"
#include "eval/reloc_methods.h"
#include "io/trajectory_io.h"
#include "sim/world_io.h"

namespace semchain::eval {
namespace fs = std::filesystem;
namespace {

// Trial k runs with seed + kTrialRunSeedOffset + k.
constexpr std::uint64_t kTrialRunSeedOffset = 1000;
// AMCL alphas = margin × the simulated odometry's, at least the minimum.
constexpr double kAlphaMargin = 2.0;
constexpr double kMinAlpha = 0.005;

// RelocBenchmarkOptions::keep_runs: what the kept runs were made from. A folder whose
// runs.json says something else is made anew.
std::string RunsStamp(const std::string& world_text, const std::string& live_world_text,
                      const RelocBenchmarkOptions& options) {
  nlohmann::json stamp = {
      {"format", 1},
      {"world", world_text},
      {"live_world", live_world_text},
      {"seed", options.seed},
      {"start_clearance", options.start_clearance},
      {"trial_turns", options.trial_turns},
      {"trial_forward", options.trial_forward},
      {"detections", options.detect ? options.detections_source : std::string("simulator")}};
  // Named only when used, so that runs kept before these settings existed stay valid.
  if (options.trial_face_open) stamp["trial_face_open"] = true;
  if (options.trial_turns_after != 0.0) stamp["trial_turns_after"] = options.trial_turns_after;
  return stamp.dump(2) + "\n";
}

// A trial's recording is complete when its trial.json names its start and seed.
std::string TrialStamp(const Pose2& start, std::uint64_t seed) {
  return nlohmann::json({{"start", {start.x, start.y, start.theta}}, {"seed", seed}}).dump() + "\n";
}

bool FileHolds(const fs::path& path, const std::string& text) {
  const Result<std::string> held = ReadFile(path);
  return held.ok() && *held == text;
}

Status CheckMethods(const RelocBenchmarkOptions& options) {
  if (options.trials < 1) return Status::Error("--trials must be at least 1");
  for (const std::string& method : options.methods) {
    if (!localization::ParseLocalizationMethod(method)) {
      return Status::Error("--methods: unknown method '" + method + "' (" +
                           localization::LocalizationMethodList() + ")");
    }
  }
  return Status::Ok();
}

// The world mapped, the live world the trials run in, and the trials' starts.
struct TrialWorlds {
  sim::World world;
  sim::World live;
  std::vector<Pose2> starts;
};

Result<TrialWorlds> LoadTrialWorlds(const fs::path& world_path, const fs::path& live_world_path,
                                    const RelocBenchmarkOptions& options) {
  Result<sim::World> world = sim::LoadWorld(world_path);
  if (!world.ok()) return world.status();
  SEMCHAIN_RETURN_IF_ERROR(sim::ValidateWorld(*world, world_path.string()));
  Result<sim::World> live = sim::LoadWorld(live_world_path);
  if (!live.ok()) return live.status();
  SEMCHAIN_RETURN_IF_ERROR(sim::ValidateWorld(*live, live_world_path.string()));
  SEMCHAIN_RETURN_IF_ERROR(CheckTrialRegionInWorld(*live, live_world_path.string()));
  Result<std::vector<Pose2>> starts = RelocTrialStarts(
      *live, options.trials, options.start_clearance, options.seed, live_world_path.string());
  if (!starts.ok()) return starts.status();
  return TrialWorlds{std::move(*world), std::move(*live), std::move(*starts)};
}

// The folder the runs are made in (RelocBenchmarkOptions::work_dir and keep_runs).
struct RunsFolder {
  fs::path work;
  bool keep = false;
  bool reuse = false;  // it holds the kept runs of these worlds and settings
  std::string stamp;   // its runs.json, when kept
};

// Removes a folder when it goes out of scope (an empty path: nothing).
struct RemoveOnExit {
  fs::path path;
  ~RemoveOnExit() {
    std::error_code error;
    if (!path.empty()) fs::remove_all(path, error);
  }
};

// Empties the work folder unless it holds runs to reuse, and makes sure it can be written.
Result<RunsFolder> OpenRunsFolder(const fs::path& world_path, const fs::path& live_world_path,
                                  const RelocBenchmarkOptions& options) {
  RunsFolder folder;
  folder.keep = options.keep_runs;
  if (folder.keep && options.work_dir.empty()) {
    return Status::Error("bench reloc: keeping the runs needs a folder for them");
  }
  folder.work =
      options.work_dir.empty()
          ? fs::temp_directory_path() / ("semchain_bench_reloc_" + std::to_string(::getpid()))
          : options.work_dir;
  const fs::path& work = folder.work;
  std::error_code ignored;
  if (folder.keep) {
    Result<std::string> world_text = ReadFile(world_path);
    if (!world_text.ok()) return world_text.status();
    Result<std::string> live_text = ReadFile(live_world_path);
    if (!live_text.ok()) return live_text.status();
    folder.stamp = RunsStamp(*world_text, *live_text, options);
    folder.reuse = FileHolds(work / "runs.json", folder.stamp);
    if (!folder.reuse && fs::exists(work) && !fs::is_empty(work, ignored) &&
        !fs::exists(work / "runs.json")) {
      // Never empty a folder that is not ours.
      return Status::Error(work.string() +
                           ": not empty and not a bench reloc runs folder (no runs.json)");
    }
  }
  if (!folder.reuse) fs::remove_all(work, ignored);
  SEMCHAIN_RETURN_IF_ERROR(EnsureWritableDirectory(work));
  return folder;
}

// The mapping run's map: read back from the kept runs, or built (and kept when asked).
Result<RelocBuiltMap> MapWorld(const sim::World& world, const fs::path& world_path,
                               const RelocBenchmarkOptions& options, const RunsFolder& folder) {
  const fs::path mapping = folder.work / "mapping";
  Result<RelocBuiltMap> built =
      folder.reuse ? ReadRelocMap(mapping, options.seed) : BuildRelocMap(world, options, mapping);
  if (!built.ok()) return built.status();
  if (folder.keep && !folder.reuse) {
    SEMCHAIN_RETURN_IF_ERROR(WriteRelocMap(*built, mapping));
    // Last: a folder interrupted before this is made anew.
    SEMCHAIN_RETURN_IF_ERROR(WriteFileAtomically(folder.work / "runs.json", folder.stamp));
  }
  if (built->semantic.objects.empty()) {
    return Status::Error(world_path.string() + ": the mapping run found no objects");
  }
  return built;
}

// The truth carried into the SLAM map's frame, from the mapping run's trajectories.
Result<MapFrame> MappingRunFrame(const RelocBuiltMap& built, const RunsFolder& folder) {
  Result<std::vector<StampedPose>> mapping_truth =
      ReadTrajectory(folder.work / "mapping" / "truth.txt");
  if (!mapping_truth.ok()) return mapping_truth.status();
  return MapFrame::FromTrajectories(built.trajectory, *mapping_truth);
}

// AMCL's odometry noise is a property of the robot: as a user tunes it for theirs, it is set
// from the simulated robot's odometry model (the same for every method), with a margin.
localization::AmclOptions AmclForRobot(const sim::World& live) {
  localization::AmclOptions amcl;
  const std::array<double, 4>& noise = live.robot.odometry_noise;
  amcl.alpha1 = std::max(kMinAlpha, kAlphaMargin * noise[0]);
  amcl.alpha2 = std::max(kMinAlpha, kAlphaMargin * noise[1]);
  amcl.alpha3 = std::max(kMinAlpha, kAlphaMargin * noise[2]);
  amcl.alpha4 = std::max(kMinAlpha, kAlphaMargin * noise[3]);
  return amcl;
}

// semantic-amcl-bow's bag of words, when that method runs.
Status AddRecognizer(const RelocBenchmarkOptions& options, const RelocBuiltMap& built,
                     const RunsFolder& folder, localization::LocalizerMap* map) {
  if (std::find(options.methods.begin(), options.methods.end(), "semantic-amcl-bow") ==
      options.methods.end()) {
    return Status::Ok();
  }
  auto recognizer = BuildRelocRecognizer(built, folder.work / "mapping", options.seed);
  if (!recognizer.ok()) return recognizer.status();
  map->recognizer = *recognizer;
  return Status::Ok();
}

// The result's description of the benchmark, before any trial.
RelocBenchmarkResult ResultHeader(const fs::path& world_path, const fs::path& live_world_path,
                                  const RelocBenchmarkOptions& options,
                                  const RelocBuiltMap& built) {
  RelocBenchmarkResult result;
  result.world = world_path.string();
  result.live_world = live_world_path.string();
  result.detections_source = options.detect ? options.detections_source : "simulator";
  result.trials = options.trials;
  result.seed = options.seed;
  result.trial_turns = options.trial_turns;
  result.trial_forward = options.trial_forward;
  result.trial_face_open = options.trial_face_open;
  result.trial_turns_after = options.trial_turns_after;
  result.map_objects = static_cast<int>(built.semantic.objects.size());
  result.map_ate_m = built.ate;
  return result;
}

fs::path TrialDirectory(const RunsFolder& folder, int k) {
  return folder.work / ("trial_" + std::to_string(k));
}

// Trial k's recording from 'start': the one kept in its folder, or simulated anew (and kept
// when asked).
Result<RelocTrialRun> TrialRecording(const sim::World& live, const Pose2& start, int k,
                                     const RelocBenchmarkOptions& options,
                                     const RunsFolder& folder) {
  const fs::path run = TrialDirectory(folder, k);
  const std::uint64_t trial_seed = options.seed + kTrialRunSeedOffset + k;
  const std::string trial_stamp = TrialStamp(start, trial_seed);
  const bool kept_trial = folder.keep && FileHolds(run / "trial.json", trial_stamp);
  std::error_code ignored;
  if (folder.keep && !kept_trial) fs::remove_all(run, ignored);
  Result<RelocTrialRun> trial = kept_trial
                                    ? LoadRelocTrial(trial_seed, options, run)
                                    : SimulateRelocTrial(live, start, trial_seed, options, run);
  if (!trial.ok()) return trial.status();
  if (folder.keep && !kept_trial) {
    SEMCHAIN_RETURN_IF_ERROR(WriteFileAtomically(run / "trial.json", trial_stamp));
  }
  return trial;
}

// Every method on trial k's recording, scored into 'result'.
void RunMethods(const RelocTrialRun& trial, int k, const Pose2& start,
                const localization::LocalizerMap& map, const MapFrame& map_frame,
                const RelocBenchmarkOptions& options, RelocBenchmarkResult* result) {
  for (const std::string& method : options.methods) {
    const localization::RelocTrace trace = RunRelocMethod(
        *localization::ParseLocalizationMethod(method), map, options.method, trial.inputs);
    const RelocTrialOutcome outcome = ScoreRelocTrace(trace, trial.truth, options, &map_frame);
    AccumulateRelocOutcome(outcome, &result->methods[method]);
    result->runs[method].push_back(RelocTrialRecordOf(k, start, trace, outcome));
  }
}

}  // namespace

Result<RelocBenchmarkResult> RunRelocBenchmark(const fs::path& world_path,
                                               const fs::path& live_world_path,
                                               const RelocBenchmarkOptions& options,
                                               const std::function<void(int, int)>& progress) {
  SEMCHAIN_RETURN_IF_ERROR(CheckMethods(options));
  Result<TrialWorlds> worlds = LoadTrialWorlds(world_path, live_world_path, options);
  if (!worlds.ok()) return worlds.status();
  Result<RunsFolder> folder = OpenRunsFolder(world_path, live_world_path, options);
  if (!folder.ok()) return folder.status();
  const RemoveOnExit cleanup{folder->keep ? fs::path() : folder->work};
  Result<RelocBuiltMap> built = MapWorld(worlds->world, world_path, options, *folder);
  if (!built.ok()) return built.status();
  Result<MapFrame> map_frame = MappingRunFrame(*built, *folder);
  if (!map_frame.ok()) return map_frame.status();
  localization::LocalizerMap map(built->occupancy, built->semantic, AmclForRobot(worlds->live),
                                 options.prelocalization,
                                 localization::ScanMatchRelocalizerOptions());
  SEMCHAIN_RETURN_IF_ERROR(AddRecognizer(options, *built, *folder, &map));

  RelocBenchmarkResult result = ResultHeader(world_path, live_world_path, options, *built);
  std::error_code ignored;
  for (int k = 0; k < options.trials; ++k) {
    const Pose2& start = worlds->starts[static_cast<std::size_t>(k)];
    Result<RelocTrialRun> trial = TrialRecording(worlds->live, start, k, options, *folder);
    if (!trial.ok()) return trial.status();
    RunMethods(*trial, k, start, map, *map_frame, options, &result);
    if (!folder->keep) fs::remove_all(TrialDirectory(*folder, k), ignored);
    if (progress) progress(k + 1, options.trials);
  }
  for (auto& [name, stats] : result.methods) FinishRelocStats(&stats);
  return result;
}

}  // namespace semchain::eval
