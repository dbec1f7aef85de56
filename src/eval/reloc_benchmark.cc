#include "eval/reloc_benchmark.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "bow/bow_vocabulary.h"
#include "bow/keyframe_recognizer.h"
#include "bow/orb_features.h"
#include "bow/run_features.h"
#include "core/angles.h"
#include "core/atomic_file.h"
#include "core/rng.h"
#include "eval/ate.h"
#include "eval/reloc_methods.h"
#include "io/camera_io.h"
#include "io/carmen.h"
#include "io/detections_io.h"
#include "io/rgbd_frame_io.h"
#include "io/trajectory_io.h"
#include "mapping/map_io.h"
#include "mapping/slam_pipeline.h"
#include "semantic/keyframe_selection.h"
#include "semantic/keyframes.h"
#include "semantic/semantic_map_io.h"
#include "semantic/semantic_run.h"
#include "sim/scene.h"
#include "sim/simulator.h"
#include "sim/world_io.h"

namespace semchain::eval {
namespace fs = std::filesystem;
namespace {

// Random streams of the benchmark (MakeRng(seed, stream)).
constexpr std::uint64_t kTrialPoseStream = 31;
constexpr std::uint64_t kTrialRunSeedOffset = 1000;
// AMCL alphas = margin × the simulated odometry's, at least the minimum.
constexpr double kAlphaMargin = 2.0;
constexpr double kMinAlpha = 0.005;

struct BuiltMap {
  mapping::MapImage occupancy;
  semantic::SemanticMap semantic;
  std::vector<semantic::Keyframe> keyframes;
  double ate = 0.0;
  std::vector<StampedPose> trajectory;  // the mapping run's SLAM estimate
};

// The SLAM of a simulated mapping run in 'run', with the benchmark's options.
Result<mapping::SlamResult> MappingSlam(const fs::path& run, std::uint64_t seed) {
  Result<carmen::Log> log = carmen::ReadLog(run / "log.clf");
  if (!log.ok()) return log.status();
  Result<std::vector<StampedScan>> scans = mapping::ScansFromLog(*log, (run / "log.clf").string());
  if (!scans.ok()) return scans.status();
  mapping::SlamOptions slam_options;
  slam_options.rbpf.seed = seed;
  return mapping::RunSlam(*scans, slam_options);
}

// The bag of words of the mapping run (seed 000 §3.1 steps 1–2): a vocabulary trained on its
// frames and its keyframes described with it.
Result<std::shared_ptr<const bow::KeyframeRecognizer>> BuildRecognizer(const BuiltMap& built,
                                                                       const fs::path& run,
                                                                       std::uint64_t seed) {
  Result<std::vector<fs::path>> images = bow::ListColorFrames(run);
  if (!images.ok()) return images.status();
  Result<std::vector<cv::Mat>> descriptors =
      bow::ExtractImageDescriptors(*images, bow::OrbOptions());
  if (!descriptors.ok()) return descriptors.status();
  bow::VocabularyOptions options;
  options.seed = seed;
  Result<bow::Vocabulary> vocabulary = bow::Vocabulary::Train(*descriptors, options);
  if (!vocabulary.ok()) return vocabulary.status();
  semantic::KeyframeDatabase database{run.string(),
                                      semantic::SelectCoveringKeyframes(built.keyframes)};
  Result<bow::KeyframeRecognizer> recognizer = bow::KeyframeRecognizer::Build(
      std::move(*vocabulary), std::move(database), bow::KeyframeRecognizerOptions(), run);
  if (!recognizer.ok()) return recognizer.status();
  return std::shared_ptr<const bow::KeyframeRecognizer>(
      std::make_shared<bow::KeyframeRecognizer>(std::move(*recognizer)));
}

// The run's detections: options.detect's, or the simulator's RUN/detections.jsonl.
Result<std::vector<FrameDetections>> RunDetections(const RelocBenchmarkOptions& options,
                                                   const fs::path& run) {
  if (options.detect) return options.detect(run);
  return ReadDetectionsJsonl(run / "detections.jsonl");
}

Result<BuiltMap> BuildMap(const sim::World& world, const RelocBenchmarkOptions& options,
                          const fs::path& run) {
  const std::uint64_t seed = options.seed;
  sim::SimulationOptions simulation;
  simulation.seed = seed;
  simulation.show_progress = false;
  SEMCHAIN_RETURN_IF_ERROR(sim::Simulate(world, simulation, run));
  Result<mapping::SlamResult> slam_result = MappingSlam(run, seed);
  if (!slam_result.ok()) return slam_result.status();
  const mapping::SlamResult& slam = *slam_result;

  BuiltMap built;
  built.occupancy = mapping::GridToMapImage(slam.map);
  built.trajectory = slam.trajectory;
  Result<std::vector<StampedPose>> truth = ReadTrajectory(run / "truth.txt");
  if (!truth.ok()) return truth.status();
  Result<AteResult> ate = EvaluateAte(slam.trajectory, *truth);
  if (ate.ok()) built.ate = ate->ate_rmse_m;
  semantic::SemanticRunInputs inputs;
  inputs.run_dir = run;
  inputs.occupancy = built.occupancy;
  inputs.trajectory = slam.trajectory;
  if (options.detect) {
    Result<std::vector<FrameDetections>> detections = options.detect(run);
    if (!detections.ok()) return detections.status();
    inputs.detections = std::move(*detections);
  }
  Result<semantic::SemanticMappingResult> mapped =
      semantic::MapRun(inputs, semantic::SemanticMapOptions());
  if (!mapped.ok()) return mapped.status();
  built.semantic = mapped->map;
  built.keyframes = mapped->keyframes;
  return built;
}

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

// The mapping run's map as kept in RUN/map: map.yaml, semantic.json, keyframes.json, ate.json.
Status WriteBuiltMap(const BuiltMap& built, const fs::path& run) {
  const fs::path dir = run / "map";
  SEMCHAIN_RETURN_IF_ERROR(EnsureWritableDirectory(dir));
  SEMCHAIN_RETURN_IF_ERROR(mapping::WriteMap(dir / "map.yaml", built.occupancy));
  SEMCHAIN_RETURN_IF_ERROR(semantic::WriteSemanticJson(dir / "semantic.json", built.semantic));
  SEMCHAIN_RETURN_IF_ERROR(
      semantic::WriteKeyframes(dir / "keyframes.json", {"..", built.keyframes}));
  SEMCHAIN_RETURN_IF_ERROR(WriteTrajectory(dir / "trajectory.txt", built.trajectory));
  return WriteFileAtomically(dir / "ate.json",
                             nlohmann::json({{"ate_rmse_m", built.ate}}).dump() + "\n");
}

Result<BuiltMap> ReadBuiltMap(const fs::path& run, std::uint64_t seed) {
  const fs::path dir = run / "map";
  BuiltMap built;
  Result<mapping::MapImage> occupancy = mapping::ReadMap(dir / "map.yaml");
  if (!occupancy.ok()) return occupancy.status();
  built.occupancy = std::move(*occupancy);
  Result<semantic::SemanticMap> map = semantic::ReadSemanticJson(dir / "semantic.json");
  if (!map.ok()) return map.status();
  built.semantic = std::move(*map);
  Result<semantic::KeyframeDatabase> keyframes = semantic::ReadKeyframes(dir / "keyframes.json");
  if (!keyframes.ok()) return keyframes.status();
  built.keyframes = std::move(keyframes->keyframes);
  Result<std::string> ate = ReadFile(dir / "ate.json");
  if (!ate.ok()) return ate.status();
  const nlohmann::json parsed = nlohmann::json::parse(*ate, nullptr, /*allow_exceptions=*/false);
  if (!parsed.is_object() || !parsed.contains("ate_rmse_m") || !parsed["ate_rmse_m"].is_number()) {
    return Status::Error((dir / "ate.json").string() + ": expected {\"ate_rmse_m\": number}");
  }
  built.ate = parsed["ate_rmse_m"].get<double>();
  if (fs::exists(dir / "trajectory.txt")) {
    Result<std::vector<StampedPose>> trajectory = ReadTrajectory(dir / "trajectory.txt");
    if (!trajectory.ok()) return trajectory.status();
    built.trajectory = std::move(*trajectory);
  } else {
    // Kept before the trajectory was: the SLAM is deterministic for its seed, so running it
    // again gives the kept map's trajectory.
    Result<mapping::SlamResult> slam = MappingSlam(run, seed);
    if (!slam.ok()) return slam.status();
    built.trajectory = slam->trajectory;
    SEMCHAIN_RETURN_IF_ERROR(WriteTrajectory(dir / "trajectory.txt", built.trajectory));
  }
  return built;
}

// The trial region must lie inside the walls' extent (the map can cover nothing else).
Status CheckTrialRegionInWorld(const sim::World& world, const std::string& source) {
  if (world.trial_region.size() < 3) {
    return Status::Error(source + ": trial_region: the live world needs a trial region");
  }
  Eigen::Vector2d low(1e300, 1e300), high(-1e300, -1e300);
  for (const auto& wall : world.walls) {
    for (const Eigen::Vector2d& p : wall) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
  }
  for (const Eigen::Vector2d& p : world.trial_region) {
    if ((p.array() < low.array()).any() || (p.array() > high.array()).any()) {
      char text[160];
      std::snprintf(text, sizeof(text),
                    ": trial_region: point (%.2f, %.2f) lies outside the map (walls span "
                    "(%.2f, %.2f) to (%.2f, %.2f))",
                    p.x(), p.y(), low.x(), low.y(), high.x(), high.y());
      return Status::Error(source + text);
    }
  }
  return Status::Ok();
}

// Uniform poses in the trial region, in free space at least 'clearance' from every surface.
Result<std::vector<Pose2>> TrialPoses(const sim::World& world, int count, double clearance,
                                      std::uint64_t seed, const std::string& source) {
  // CheckTrialRegionInWorld has made sure there is a region.
  const sim::Scene scene(world);
  Eigen::Vector2d low = world.trial_region.front();
  Eigen::Vector2d high = low;
  for (const Eigen::Vector2d& p : world.trial_region) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  Rng rng = MakeRng(seed, kTrialPoseStream);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Pose2> poses;
  constexpr int kTriesPerPose = 10000;
  for (int tries = 0; static_cast<int>(poses.size()) < count; ++tries) {
    if (tries > kTriesPerPose * count) {
      return Status::Error(source + ": trial_region: no free pose " + std::to_string(clearance) +
                           " m from every surface found in it");
    }
    // y before x, one statement each: a constructor's arguments are evaluated in an unspecified
    // order (GCC last to first, as the published trials were drawn; clang first to last).
    const double y_draw = unit(rng);
    const double x_draw = unit(rng);
    const Eigen::Vector2d p = low + (high - low).cwiseProduct(Eigen::Vector2d(x_draw, y_draw));
    if (!sim::PolygonContains(world.trial_region, p) || scene.IsOccupied(p, clearance)) continue;
    poses.emplace_back(p.x(), p.y(), NormalizeAngle(2.0 * M_PI * unit(rng)));
  }
  return poses;
}

}  // namespace

Result<RelocTrialRun> SimulateRelocTrial(const sim::World& world, const Pose2& start,
                                         std::uint64_t seed, const RelocBenchmarkOptions& options,
                                         const fs::path& run) {
  sim::SimulationOptions simulation;
  simulation.seed = seed;
  simulation.start = start;
  simulation.show_progress = false;
  simulation.route.kind = sim::RouteSpec::Kind::kTrial;
  simulation.trial.rotation_radians = 2.0 * M_PI * options.trial_turns;
  simulation.trial.forward_distance_meters = options.trial_forward;
  simulation.trial.face_most_open = options.trial_face_open;
  simulation.trial.rotation_after_radians = 2.0 * M_PI * options.trial_turns_after;
  SEMCHAIN_RETURN_IF_ERROR(sim::Simulate(world, simulation, run));
  return LoadRelocTrial(seed, options, run);
}

Result<RelocTrialRun> LoadRelocTrial(std::uint64_t seed, const RelocBenchmarkOptions& options,
                                     const fs::path& run) {
  RelocTrialRun data;
  Result<carmen::Log> log = carmen::ReadLog(run / "log.clf");
  if (!log.ok()) return log.status();
  Result<std::vector<StampedScan>> scans = mapping::ScansFromLog(*log, (run / "log.clf").string());
  if (!scans.ok()) return scans.status();
  data.inputs.scans = std::move(*scans);
  Result<std::vector<FrameDetections>> frames = RunDetections(options, run);
  if (!frames.ok()) return frames.status();
  for (const FrameDetections& frame : *frames) {
    data.inputs.frames.push_back({frame.stamp, frame.detections, ColorImagePath(run, frame.frame)});
  }
  Result<CameraInfo> camera = ReadCameraYaml(run / "camera.yaml");
  if (!camera.ok()) return camera.status();
  data.inputs.camera = camera->camera;
  data.inputs.seed = seed;
  Result<std::vector<StampedPose>> truth = ReadTrajectory(run / "truth.txt");
  if (!truth.ok()) return truth.status();
  data.truth = std::move(*truth);
  if (data.truth.size() != data.inputs.scans.size()) {
    return Status::Error(run.string() + ": truth.txt and log.clf disagree on the scan count");
  }
  return data;
}

RelocTrialOutcome ScoreRelocTrace(const localization::RelocTrace& trace,
                                  const std::vector<StampedPose>& truth,
                                  const RelocBenchmarkOptions& options, const MapFrame* map_frame) {
  RelocTrialOutcome outcome;
  const std::size_t n = trace.estimates.size();
  const auto within = [&](std::size_t i) {
    if (!trace.estimates[i]) return false;
    const Pose2& e = *trace.estimates[i];
    const Pose2& t = truth[i].pose;
    return (e.translation() - t.translation()).norm() <= options.success_distance &&
           std::abs(NormalizeAngle(e.theta - t.theta)) <= options.success_heading;
  };
  // The first scan from which the estimate stays within the tolerance to the end.
  std::size_t first = n;
  for (std::size_t i = n; i-- > 0;) {
    if (!within(i)) break;
    first = i;
  }
  if (trace.prelocalization && trace.prelocalization_scan >= 0) {
    outcome.prelocalized = true;
    const Pose2& t = truth[static_cast<std::size_t>(trace.prelocalization_scan)].pose;
    outcome.prelocalization_error =
        (trace.prelocalization->translation() - t.translation()).cwiseAbs();
    outcome.prelocalization_error_rad =
        std::abs(NormalizeAngle(trace.prelocalization->theta - t.theta));
    if (map_frame != nullptr) {
      outcome.prelocalization_error_map =
          (trace.prelocalization->translation() - map_frame->FromWorld(t).translation()).cwiseAbs();
    }
  }
  if (n > 0 && trace.estimates.back()) {
    outcome.localized = true;
    const Pose2& e = *trace.estimates.back();
    const Pose2& t = truth.back().pose;
    outcome.final_error_m = (e.translation() - t.translation()).norm();
    outcome.final_error_rad = std::abs(NormalizeAngle(e.theta - t.theta));
  }
  // A failed trial is charged what the method spent over the whole time it had: the trial up
  // to the time limit.
  const auto charge_until = [&](std::size_t last) {
    outcome.time = truth[last].timestamp - truth.front().timestamp;
    outcome.cpu = trace.cpu_seconds[last];
    outcome.search_cpu = trace.search_cpu_seconds[last];
  };
  const auto charge_failure = [&] {
    if (n == 0) return;
    std::size_t last = 0;
    while (last + 1 < n &&
           truth[last + 1].timestamp - truth.front().timestamp <= options.time_limit) {
      ++last;
    }
    charge_until(last);
  };
  if (first == n || truth[first].timestamp - truth.front().timestamp > options.time_limit) {
    charge_failure();
    return outcome;
  }
  charge_until(first);
  outcome.success = true;
  outcome.iterations = trace.iterations[first];
  const Pose2& e = *trace.estimates.back();
  const Pose2& t = truth.back().pose;
  outcome.error_m = (e.translation() - t.translation()).norm();
  outcome.error_rad = std::abs(NormalizeAngle(e.theta - t.theta));
  return outcome;
}

namespace {

void Accumulate(const RelocTrialOutcome& outcome, RelocMethodStats* stats) {
  ++stats->trials;
  if (outcome.prelocalized) {
    ++stats->prelocalized;
    stats->prelocalization_error_x_m += outcome.prelocalization_error.x();
    stats->prelocalization_error_y_m += outcome.prelocalization_error.y();
    stats->prelocalization_error_deg += outcome.prelocalization_error_rad * 180.0 / M_PI;
    stats->prelocalization_error_map_x_m += outcome.prelocalization_error_map.x();
    stats->prelocalization_error_map_y_m += outcome.prelocalization_error_map.y();
  }
  stats->mean_time_all_s += outcome.time;
  stats->mean_cpu_all_ms += 1000.0 * outcome.cpu;
  stats->mean_search_cpu_all_ms += 1000.0 * outcome.search_cpu;
  if (!outcome.success) return;
  ++stats->successes;
  stats->mean_time_s += outcome.time;
  stats->mean_cpu_ms += 1000.0 * outcome.cpu;
  stats->mean_search_cpu_ms += 1000.0 * outcome.search_cpu;
  stats->mean_iterations += outcome.iterations;
  stats->mean_error_m += outcome.error_m;
  stats->mean_error_deg += outcome.error_rad * 180.0 / M_PI;
}

void Finish(RelocMethodStats* stats) {
  stats->success_rate = stats->trials > 0 ? double(stats->successes) / stats->trials : 0.0;
  if (stats->trials > 0) {
    stats->mean_time_all_s /= stats->trials;
    stats->mean_cpu_all_ms /= stats->trials;
    stats->mean_search_cpu_all_ms /= stats->trials;
  }
  if (stats->successes > 0) {
    const double n = stats->successes;
    stats->mean_time_s /= n;
    stats->mean_cpu_ms /= n;
    stats->mean_search_cpu_ms /= n;
    stats->mean_iterations /= n;
    stats->mean_error_m /= n;
    stats->mean_error_deg /= n;
  }
  if (stats->prelocalized > 0) {
    stats->prelocalization_error_x_m /= stats->prelocalized;
    stats->prelocalization_error_y_m /= stats->prelocalized;
    stats->prelocalization_error_deg /= stats->prelocalized;
    stats->prelocalization_error_map_x_m /= stats->prelocalized;
    stats->prelocalization_error_map_y_m /= stats->prelocalized;
  }
}

}  // namespace

Result<RelocBenchmarkResult> RunRelocBenchmark(const fs::path& world_path,
                                               const fs::path& live_world_path,
                                               const RelocBenchmarkOptions& options,
                                               const std::function<void(int, int)>& progress) {
  if (options.trials < 1) return Status::Error("--trials must be at least 1");
  for (const std::string& method : options.methods) {
    if (!localization::ParseLocalizationMethod(method)) {
      return Status::Error("--methods: unknown method '" + method + "' (" +
                           localization::LocalizationMethodList() + ")");
    }
  }
  Result<sim::World> world = sim::LoadWorld(world_path);
  if (!world.ok()) return world.status();
  SEMCHAIN_RETURN_IF_ERROR(sim::ValidateWorld(*world, world_path.string()));
  Result<sim::World> live = sim::LoadWorld(live_world_path);
  if (!live.ok()) return live.status();
  SEMCHAIN_RETURN_IF_ERROR(sim::ValidateWorld(*live, live_world_path.string()));
  SEMCHAIN_RETURN_IF_ERROR(CheckTrialRegionInWorld(*live, live_world_path.string()));
  Result<std::vector<Pose2>> starts = TrialPoses(*live, options.trials, options.start_clearance,
                                                 options.seed, live_world_path.string());
  if (!starts.ok()) return starts.status();

  const bool keep = options.keep_runs;
  if (keep && options.work_dir.empty()) {
    return Status::Error("bench reloc: keeping the runs needs a folder for them");
  }
  const fs::path work =
      options.work_dir.empty()
          ? fs::temp_directory_path() / ("semchain_bench_reloc_" + std::to_string(::getpid()))
          : options.work_dir;
  std::error_code ignored;
  std::string stamp;
  bool reuse = false;
  if (keep) {
    Result<std::string> world_text = ReadFile(world_path);
    if (!world_text.ok()) return world_text.status();
    Result<std::string> live_text = ReadFile(live_world_path);
    if (!live_text.ok()) return live_text.status();
    stamp = RunsStamp(*world_text, *live_text, options);
    reuse = FileHolds(work / "runs.json", stamp);
    if (!reuse && fs::exists(work) && !fs::is_empty(work, ignored) &&
        !fs::exists(work / "runs.json")) {
      // Never empty a folder that is not ours.
      return Status::Error(work.string() +
                           ": not empty and not a bench reloc runs folder (no runs.json)");
    }
  }
  if (!reuse) fs::remove_all(work, ignored);
  SEMCHAIN_RETURN_IF_ERROR(EnsureWritableDirectory(work));
  struct Cleanup {
    fs::path path;
    ~Cleanup() {
      std::error_code error;
      if (!path.empty()) fs::remove_all(path, error);
    }
  } cleanup{keep ? fs::path() : work};

  Result<BuiltMap> built = reuse ? ReadBuiltMap(work / "mapping", options.seed)
                                 : BuildMap(*world, options, work / "mapping");
  if (!built.ok()) return built.status();
  if (keep && !reuse) {
    SEMCHAIN_RETURN_IF_ERROR(WriteBuiltMap(*built, work / "mapping"));
    // Last: a folder interrupted before this is made anew.
    SEMCHAIN_RETURN_IF_ERROR(WriteFileAtomically(work / "runs.json", stamp));
  }
  if (built->semantic.objects.empty()) {
    return Status::Error(world_path.string() + ": the mapping run found no objects");
  }
  Result<std::vector<StampedPose>> mapping_truth = ReadTrajectory(work / "mapping" / "truth.txt");
  if (!mapping_truth.ok()) return mapping_truth.status();
  Result<MapFrame> map_frame = MapFrame::FromTrajectories(built->trajectory, *mapping_truth);
  if (!map_frame.ok()) return map_frame.status();
  // AMCL's odometry noise is a property of the robot: as a user tunes it for theirs, it is set
  // from the simulated robot's odometry model (the same for every method), with a margin.
  localization::AmclOptions amcl;
  const std::array<double, 4>& noise = live->robot.odometry_noise;
  amcl.alpha1 = std::max(kMinAlpha, kAlphaMargin * noise[0]);
  amcl.alpha2 = std::max(kMinAlpha, kAlphaMargin * noise[1]);
  amcl.alpha3 = std::max(kMinAlpha, kAlphaMargin * noise[2]);
  amcl.alpha4 = std::max(kMinAlpha, kAlphaMargin * noise[3]);
  localization::LocalizerMap map(built->occupancy, built->semantic, amcl, options.prelocalization,
                                 localization::ScanMatchRelocalizerOptions());
  if (std::find(options.methods.begin(), options.methods.end(), "semantic-amcl-bow") !=
      options.methods.end()) {
    auto recognizer = BuildRecognizer(*built, work / "mapping", options.seed);
    if (!recognizer.ok()) return recognizer.status();
    map.recognizer = *recognizer;
  }

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
  result.map_objects = static_cast<int>(built->semantic.objects.size());
  result.map_ate_m = built->ate;
  for (int k = 0; k < options.trials; ++k) {
    const fs::path run = work / ("trial_" + std::to_string(k));
    const Pose2& trial_start = (*starts)[static_cast<std::size_t>(k)];
    const std::uint64_t trial_seed = options.seed + kTrialRunSeedOffset + k;
    const std::string trial_stamp = TrialStamp(trial_start, trial_seed);
    const bool kept_trial = keep && FileHolds(run / "trial.json", trial_stamp);
    if (keep && !kept_trial) fs::remove_all(run, ignored);
    Result<RelocTrialRun> trial =
        kept_trial ? LoadRelocTrial(trial_seed, options, run)
                   : SimulateRelocTrial(*live, trial_start, trial_seed, options, run);
    if (!trial.ok()) return trial.status();
    if (keep && !kept_trial) {
      SEMCHAIN_RETURN_IF_ERROR(WriteFileAtomically(run / "trial.json", trial_stamp));
    }
    for (const std::string& method : options.methods) {
      const localization::RelocTrace trace = RunRelocMethod(
          *localization::ParseLocalizationMethod(method), map, options.method, trial->inputs);
      const RelocTrialOutcome outcome = ScoreRelocTrace(trace, trial->truth, options, &*map_frame);
      Accumulate(outcome, &result.methods[method]);
      const Pose2& start = (*starts)[static_cast<std::size_t>(k)];
      RelocTrialRecord record;
      record.trial = k;
      record.start[0] = start.x;
      record.start[1] = start.y;
      record.start[2] = start.theta;
      record.success = outcome.success;
      record.time_s = outcome.time;
      record.cpu_ms = 1000.0 * outcome.cpu;
      record.search_cpu_ms = 1000.0 * outcome.search_cpu;
      if (!trace.search_cpu_seconds.empty()) {
        record.search_cpu_trial_ms = 1000.0 * trace.search_cpu_seconds.back();
      }
      record.localized = outcome.localized;
      record.error_m = outcome.final_error_m;
      record.error_deg = outcome.final_error_rad * 180.0 / M_PI;
      record.prelocalizations = trace.prelocalizations;
      record.single_object_prelocalizations = trace.single_object_prelocalizations;
      record.undecided_prelocalizations = trace.undecided_prelocalizations;
      record.lock_corrections = trace.lock_corrections;
      record.lock_rechecks = trace.lock_rechecks;
      if (outcome.prelocalized) {
        record.prelocalization_error =
            Eigen::Vector3d(outcome.prelocalization_error.x(), outcome.prelocalization_error.y(),
                            outcome.prelocalization_error_rad * 180.0 / M_PI);
        record.prelocalization_error_map = outcome.prelocalization_error_map;
      }
      result.runs[method].push_back(record);
    }
    if (!keep) fs::remove_all(run, ignored);
    if (progress) progress(k + 1, options.trials);
  }
  for (auto& [name, stats] : result.methods) Finish(&stats);
  return result;
}

std::string RelocResultsJson(const RelocBenchmarkResult& result) {
  nlohmann::json methods = nlohmann::json::object();
  for (const auto& [name, s] : result.methods) {
    methods[name] = {{"trials", s.trials},
                     {"successes", s.successes},
                     {"success_rate", s.success_rate},
                     {"mean_time_s", s.mean_time_s},
                     {"mean_cpu_ms", s.mean_cpu_ms},
                     {"mean_search_cpu_ms", s.mean_search_cpu_ms},
                     {"mean_time_all_s", s.mean_time_all_s},
                     {"mean_cpu_all_ms", s.mean_cpu_all_ms},
                     {"mean_search_cpu_all_ms", s.mean_search_cpu_all_ms},
                     {"mean_iterations", s.mean_iterations},
                     {"mean_error_m", s.mean_error_m},
                     {"mean_error_deg", s.mean_error_deg},
                     {"prelocalized", s.prelocalized},
                     {"prelocalization_error_x_m", s.prelocalization_error_x_m},
                     {"prelocalization_error_y_m", s.prelocalization_error_y_m},
                     {"prelocalization_error_deg", s.prelocalization_error_deg},
                     {"prelocalization_error_map_x_m", s.prelocalization_error_map_x_m},
                     {"prelocalization_error_map_y_m", s.prelocalization_error_map_y_m}};
  }
  nlohmann::json runs = nlohmann::json::object();
  for (const auto& [name, records] : result.runs) {
    nlohmann::json list = nlohmann::json::array();
    for (const RelocTrialRecord& r : records) {
      nlohmann::json prelocalization_error = nullptr;
      if (r.prelocalization_error) {
        prelocalization_error = {r.prelocalization_error->x(), r.prelocalization_error->y(),
                                 r.prelocalization_error->z()};
      }
      nlohmann::json prelocalization_error_map = nullptr;
      if (r.prelocalization_error_map) {
        prelocalization_error_map = {r.prelocalization_error_map->x(),
                                     r.prelocalization_error_map->y()};
      }
      list.push_back({{"trial", r.trial},
                      {"start", {r.start[0], r.start[1], r.start[2]}},
                      {"success", r.success},
                      {"time_s", r.time_s},
                      {"cpu_ms", r.cpu_ms},
                      {"search_cpu_ms", r.search_cpu_ms},
                      {"search_cpu_trial_ms", r.search_cpu_trial_ms},
                      {"localized", r.localized},
                      {"error_m", r.error_m},
                      {"error_deg", r.error_deg},
                      {"prelocalizations", r.prelocalizations},
                      {"single_object_prelocalizations", r.single_object_prelocalizations},
                      {"undecided_prelocalizations", r.undecided_prelocalizations},
                      {"lock_corrections", r.lock_corrections},
                      {"lock_rechecks", r.lock_rechecks},
                      {"prelocalization_error", prelocalization_error},
                      {"prelocalization_error_map", prelocalization_error_map}});
    }
    runs[name] = list;
  }
  const nlohmann::json root = {{"world", result.world},
                               {"live_world", result.live_world},
                               {"detections", result.detections_source},
                               {"trials", result.trials},
                               {"seed", result.seed},
                               {"map_objects", result.map_objects},
                               {"map_ate_m", result.map_ate_m},
                               {"trial_protocol",
                                {{"turns", result.trial_turns},
                                 {"forward_m", result.trial_forward},
                                 {"face_open", result.trial_face_open},
                                 {"turns_after", result.trial_turns_after}}},
                               {"methods", methods},
                               {"runs", runs}};
  return root.dump(2) + "\n";
}

std::string RelocResultsMarkdown(const RelocBenchmarkResult& result) {
  std::string text = "# bench reloc\n\nworld `" + result.world + "`, live world `" +
                     result.live_world + "`, " + std::to_string(result.trials) + " trials, seed " +
                     std::to_string(result.seed) + "; map from SLAM (ATE " +
                     std::to_string(result.map_ate_m) + " m), " +
                     std::to_string(result.map_objects) +
                     " objects; detections: " + result.detections_source + "\n\n";
  const auto turns = [](double n) { return n == 1.0 ? "turn" : "turns"; };
  char protocol[256];
  std::snprintf(protocol, sizeof(protocol),
                "Trials: %g %s in place, then a drive of at most %g m %s", result.trial_turns,
                turns(result.trial_turns), result.trial_forward,
                result.trial_face_open ? "towards the most open heading" : "straight on");
  text += protocol;
  if (result.trial_turns_after > 0.0) {
    std::snprintf(protocol, sizeof(protocol), ", then %g more %s in place there",
                  result.trial_turns_after, turns(result.trial_turns_after));
    text += protocol;
  }
  text += ".\n\n";
  text +=
      "Time, CPU and search CPU: means over the successful trials (until convergence), then "
      "over all trials (a failed trial charged for its whole time, up to the limit). "
      "Pre-localization error: the first hypothesis a method accepted, against the truth and "
      "against the truth carried into the SLAM map's frame (the map's own error taken out).\n\n"
      "| method | success | mean time (s) | mean CPU (ms) | search CPU (ms) | all trials: "
      "time (s) / CPU (ms) / search CPU (ms) | iterations | error (m) | error (deg) "
      "| pre-localization error x / y (m) | in the map's frame x / y (m) |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [name, s] : result.methods) {
    const bool scan_matcher =
        localization::IsScanMatcherMethod(*localization::ParseLocalizationMethod(name));
    char search_cpu[32] = "–";
    char search_cpu_all[32] = "–";
    if (scan_matcher) {
      std::snprintf(search_cpu, sizeof(search_cpu), "%.2f", s.mean_search_cpu_ms);
      std::snprintf(search_cpu_all, sizeof(search_cpu_all), "%.2f", s.mean_search_cpu_all_ms);
    }
    char prelocalization[64] = "–";
    char prelocalization_map[64] = "–";
    if (s.prelocalized > 0) {
      std::snprintf(prelocalization, sizeof(prelocalization), "%.3f / %.3f",
                    s.prelocalization_error_x_m, s.prelocalization_error_y_m);
      std::snprintf(prelocalization_map, sizeof(prelocalization_map), "%.3f / %.3f",
                    s.prelocalization_error_map_x_m, s.prelocalization_error_map_y_m);
    }
    char line[512];
    std::snprintf(line, sizeof(line),
                  "| %s | %d/%d (%.1f %%) | %.2f | %.1f | %s | %.2f / %.1f / %s | %.1f | %.3f | "
                  "%.2f | %s | %s |\n",
                  name.c_str(), s.successes, s.trials, 100.0 * s.success_rate, s.mean_time_s,
                  s.mean_cpu_ms, search_cpu, s.mean_time_all_s, s.mean_cpu_all_ms, search_cpu_all,
                  s.mean_iterations, s.mean_error_m, s.mean_error_deg, prelocalization,
                  prelocalization_map);
    text += line;
  }
  return text;
}

}  // namespace semchain::eval
