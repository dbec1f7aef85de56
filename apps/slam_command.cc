// semchain slam --log L.clf --out MAP [--particles N] [--config C.yaml] [--seed S] [--depth RUN]
// RBPF SLAM (seed 003, DESIGN.md §3.2) on a CARMEN log: writes MAP/map.yaml + map.pgm
// (map_server), MAP/map.png, MAP/trajectory.txt (a pose for every scan) and MAP/slam.json.
// With --depth RUN the run's depth frames are fused in (seed 004, DESIGN.md §3.3): map.* is
// then the fused map, map_lidar.* the lidar-only one and map_depth.* the depth-only one.
// With --semantic RUN the semantic map grows while SLAM runs (one pass, DESIGN.md §1): also
// MAP/semantic.json, keyframes.json, semantic.png (what `semantic` writes on the final
// trajectory, equal to it) and semantic_growth.json (first sighting of each object, object
// count over time, per-frame and re-projection costs). The folder is staged beside MAP and
// renamed into place (semantic::WriteMapFolder): a crash never leaves a half-written map.
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "apps/command.h"
#include "apps/shipped_file.h"
#include "apps/slam_semantic.h"
#include "core/atomic_file.h"
#include "core/progress_bar.h"
#include "io/carmen.h"
#include "io/trajectory_io.h"
#include "mapping/depth_mapping.h"
#include "mapping/map_io.h"
#include "mapping/slam_options_io.h"
#include "mapping/slam_pipeline.h"
#include "semantic/map_folder_writer.h"

namespace semchain::app {
namespace {

struct SlamArgs {
  std::string log;
  std::string out;
  std::string config;
  std::string variant;
  std::string every_scan;
  std::string depth_run;
  std::optional<int> particles;
  std::optional<int> seed;
  std::optional<int> threads;
  std::optional<int> max_scans;
  bool raw_odometry = false;
  // --pose-graph / --no-pose-graph: override the config's pose_graph.enabled when given.
  bool pose_graph_on = false;
  bool pose_graph_off = false;
  SlamSemanticArgs semantic;
};

Result<mapping::SlamOptions> BuildOptions(const SlamArgs& args) {
  mapping::SlamOptions options;
  if (!args.config.empty()) {
    SEMCHAIN_RETURN_IF_ERROR(mapping::LoadSlamOptions(args.config, &options));
  }
  if (!args.variant.empty())
    SEMCHAIN_RETURN_IF_ERROR(mapping::ApplyVariant(args.variant, &options));
  if (args.particles) options.rbpf.particles = *args.particles;
  if (args.seed) options.rbpf.seed = static_cast<std::uint64_t>(*args.seed);
  if (args.threads) options.rbpf.threads = *args.threads;
  if (!args.every_scan.empty()) options.every_scan.method = args.every_scan;
  if (args.pose_graph_on) options.pose_graph = true;
  if (args.pose_graph_off) options.pose_graph = false;
  std::string error;
  if (!options.Validate(&error)) return Status::Error("invalid SLAM options: " + error);
  return options;
}

std::string StatisticsJson(const mapping::SlamResult& result, const mapping::SlamOptions& options,
                           double seconds) {
  const mapping::RbpfStatistics& s = result.statistics;
  nlohmann::json json = {{"scans", s.scans},
                         {"processed", s.processed},
                         {"localized", result.every_scan.matched},
                         {"localized_searched", result.every_scan.searched},
                         {"localized_replaced", result.every_scan.replaced},
                         {"particles", options.rbpf.particles},
                         {"seed", options.rbpf.seed},
                         {"annealing", options.rbpf.annealing.enabled},
                         {"genetic", options.rbpf.genetic.enabled},
                         {"resamplings", s.resamplings},
                         {"genetic_resamplings", s.genetic_resamplings},
                         {"crossovers", s.crossovers},
                         {"mutations", s.mutations},
                         {"unmatched_updates", s.unmatched},
                         {"recoveries", s.recoveries},
                         {"mean_effective_sample_size", s.mean_effective_sample_size},
                         {"mean_alpha", s.mean_alpha},
                         {"every_scan", options.every_scan.method},
                         {"laser_odometry_rejected", result.laser_odometry_rejected},
                         {"laser_odometry_seconds", result.laser_odometry_seconds},
                         {"filter_seconds", result.filter_seconds},
                         {"every_scan_seconds", result.every_scan_seconds},
                         {"slam_seconds", seconds}};
  if (options.pose_graph) {
    const mapping::LoopClosureStatistics& l = result.loop_closure;
    json["pose_graph"] = {{"nodes", l.nodes},
                          {"submaps", l.submaps},
                          {"searches", l.searches},
                          {"closures_found", l.found},
                          {"closures_accepted", l.accepted},
                          {"closures_rejected", l.rejected},
                          {"closures_gated", l.gated},
                          {"motion_edges_loosened", l.loosened},
                          {"optimizations", l.optimizations},
                          {"online", options.loop_closure.online},
                          {"follows", l.follows},
                          {"motion_noise_scale", l.motion_noise_scale},
                          {"search_seconds", l.search_seconds},
                          {"built_submaps_peak_mb", l.built_submaps_peak_megabytes},
                          {"optimizer_seconds", l.optimizer_seconds},
                          {"residuals", l.residuals}};
  }
  return json.dump(2) + "\n";
}

// The whole map folder, staged and renamed into place (semantic::WriteMapFolder): the map,
// trajectory and semantic files, then what only the CLI writes (the lidar and depth maps,
// map.png, slam.json, the semantic drawing and growth report).
Status WriteOutputs(const std::filesystem::path& out, const mapping::SlamResult& result,
                    const std::optional<mapping::DepthFusionResult>& depth,
                    const std::string& statistics, const mapping::MapImage& map,
                    const SlamSemantic* semantic,
                    const std::optional<semantic::LiveSemanticResult>& live,
                    const std::optional<semantic::KeyframeDatabase>& keyframes) {
  const semantic::MapFolderContents contents{map, result.trajectory,
                                             live ? &live->mapping.map : nullptr,
                                             keyframes ? &*keyframes : nullptr};
  return semantic::WriteMapFolder(out, contents, [&](const std::filesystem::path& dir) {
    if (depth) {
      SEMCHAIN_RETURN_IF_ERROR(
          mapping::WriteMap(dir / "map_lidar.yaml", mapping::GridToMapImage(result.map)));
      SEMCHAIN_RETURN_IF_ERROR(
          mapping::WriteMap(dir / "map_depth.yaml", mapping::GridToMapImage(depth->depth)));
    }
    SEMCHAIN_RETURN_IF_ERROR(mapping::WriteMapPng(dir / "map.png", map));
    SEMCHAIN_RETURN_IF_ERROR(WriteFileAtomically(dir / "slam.json", statistics));
    if (live) SEMCHAIN_RETURN_IF_ERROR(semantic->WriteExtras(dir, map, *live));
    return Status::Ok();
  });
}

// Everything the SLAM run needs, read and checked before the (long) run starts.
struct SlamInputs {
  mapping::SlamOptions options;
  std::vector<StampedScan> scans;
  std::optional<mapping::DepthRun> depth_run;
  std::unique_ptr<SlamSemantic> semantic;
};

Result<std::vector<StampedScan>> ReadScans(const SlamArgs& args) {
  const Result<carmen::Log> log = carmen::ReadLog(args.log);
  if (!log.ok()) return log.status();
  mapping::ReversedOdometryRepair repair;
  Result<std::vector<StampedScan>> scans =
      mapping::ScansFromLog(*log, args.log, args.raw_odometry ? nullptr : &repair);
  if (!scans.ok()) return scans.status();
  if (repair.steps > 0) {
    spdlog::warn(
        "slam: {}: the odometry moved forward while its velocity was negative in {} steps "
        "({:.1f} m): reversed them (--raw-odometry keeps the log's odometry)",
        args.log, repair.steps, repair.meters);
  }
  if (args.max_scans && static_cast<std::size_t>(*args.max_scans) < scans->size()) {
    scans->resize(static_cast<std::size_t>(*args.max_scans));
  }
  return scans;
}

Result<SlamInputs> ReadInputs(const SlamArgs& args) {
  SlamInputs inputs;
  Result<mapping::SlamOptions> options = BuildOptions(args);
  if (!options.ok()) return options.status();
  inputs.options = std::move(*options);
  Result<std::vector<StampedScan>> scans = ReadScans(args);
  if (!scans.ok()) return scans.status();
  inputs.scans = std::move(*scans);
  // The run's camera and frame list are checked before the (long) SLAM run.
  if (!args.depth_run.empty()) {
    Result<mapping::DepthRun> loaded = mapping::LoadDepthRun(args.depth_run);
    if (!loaded.ok()) return loaded.status();
    inputs.depth_run = std::move(*loaded);
  }
  if (!args.semantic.run.empty()) {
    Result<std::unique_ptr<SlamSemantic>> opened =
        SlamSemantic::Open(args.semantic, inputs.options.rbpf.grid.resolution_meters);
    if (!opened.ok()) return opened.status();
    inputs.semantic = std::move(*opened);
  }
  SEMCHAIN_RETURN_IF_ERROR(EnsureWritableDirectory(args.out));
  return inputs;
}

struct SlamRun {
  mapping::SlamResult result;
  double seconds = 0.0;
};

// The filter over the scans; the semantic map, when asked for, grows with it.
SlamRun RunFilter(SlamInputs& inputs) {
  const mapping::SlamOptions& options = inputs.options;
  spdlog::info("slam: {} scans, {} particles, annealing {}, genetic resampling {}",
               inputs.scans.size(), options.rbpf.particles,
               options.rbpf.annealing.enabled ? "on" : "off",
               options.rbpf.genetic.enabled ? "on" : "off");
  ProgressBar bar("slam", 2 * inputs.scans.size());
  const auto start = std::chrono::steady_clock::now();
  std::function<void(const mapping::SlamStep&)> observe;
  if (inputs.semantic) {
    inputs.semantic->StartPreparing();
    observe = [&inputs](const mapping::SlamStep& step) { inputs.semantic->Observe(step); };
  }
  mapping::SlamResult result = mapping::RunSlam(
      inputs.scans, options, [&bar](std::size_t done) { bar.Update(done); }, observe);
  bar.Finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return {std::move(result), seconds};
}

Result<mapping::DepthFusionResult> FuseDepth(const mapping::DepthRun& depth_run,
                                             const mapping::SlamResult& result) {
  ProgressBar depth_bar("depth fusion", depth_run.frames.size());
  Result<mapping::DepthFusionResult> fused =
      mapping::FuseDepthRun(depth_run, result.map, result.trajectory, {},
                            [&depth_bar](std::size_t done) { depth_bar.Update(done); });
  depth_bar.Finish();
  if (!fused.ok()) return fused.status();
  spdlog::info("slam: fused {} depth frames into the map", fused->frames);
  return fused;
}

void LogStatistics(const SlamInputs& inputs, const SlamRun& run) {
  const mapping::SlamResult& result = run.result;
  spdlog::info(
      "slam: processed {} scans, localized {} of {} in the final map ({} searched, {} moved by "
      "the search), {:.1f} s",
      result.statistics.processed, result.every_scan.matched, inputs.scans.size(),
      result.every_scan.searched, result.every_scan.replaced, run.seconds);
  if (!inputs.options.pose_graph) return;
  const mapping::LoopClosureStatistics& l = result.loop_closure;
  spdlog::info(
      "slam: pose graph: {} nodes, {} submaps, loop closures {} found, {} accepted, {} "
      "rejected by the other closures, {} not added (off the motion's prediction); {} motion "
      "edges loosened where the filter snapped onto older map; search {:.1f} s (submaps built "
      "for it: {:.0f} MB at most), optimizer {:.2f} s",
      l.nodes, l.submaps, l.found, l.accepted, l.rejected, l.gated, l.loosened, l.search_seconds,
      l.built_submaps_peak_megabytes, l.optimizer_seconds);
  if (inputs.options.loop_closure.online) {
    spdlog::info("slam: pose graph online: the particles followed it {} times", l.follows);
  }
}

int RunSlamCommand(const SlamArgs& args) {
  Result<SlamInputs> inputs = ReadInputs(args);
  if (!inputs.ok()) return ReportError(inputs.status());
  SlamRun run = RunFilter(*inputs);
  std::optional<mapping::DepthFusionResult> depth;
  if (inputs->depth_run) {
    Result<mapping::DepthFusionResult> fused = FuseDepth(*inputs->depth_run, run.result);
    if (!fused.ok()) return ReportError(fused.status());
    depth = std::move(*fused);
  }
  // Everything is computed before anything is written; the folder is written atomically.
  std::optional<semantic::LiveSemanticResult> live;
  const mapping::MapImage map = mapping::GridToMapImage(depth ? depth->fused : run.result.map);
  // Without depth fusion the grid is not written again; a campus grid takes hundreds of MB,
  // more than the images the folder is written from.
  if (!depth) run.result.map = mapping::OccupancyGrid();
  std::optional<semantic::KeyframeDatabase> keyframes;
  if (inputs->semantic) {
    Result<semantic::LiveSemanticResult> finished =
        inputs->semantic->Finish(run.result.trajectory, map);
    if (!finished.ok()) return ReportError(finished.status());
    live = std::move(*finished);
    keyframes = inputs->semantic->Keyframes(*live);
  }
  const Status written = WriteOutputs(args.out, run.result, depth,
                                      StatisticsJson(run.result, inputs->options, run.seconds), map,
                                      inputs->semantic.get(), live, keyframes);
  if (!written.ok()) return ReportError(written);
  if (live) {
    std::printf("%s\nwrote %s\n",
                SemanticSummary(live->mapping, keyframes->keyframes.size()).c_str(),
                (std::filesystem::path(args.out) / "semantic.json").string().c_str());
  }
  LogStatistics(*inputs, run);
  return 0;
}

}  // namespace

void AddSlamCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SlamArgs>();
  CLI::App* command = app.add_subcommand(
      "slam", "RBPF SLAM on a CARMEN log: map_server map and a pose for every scan");
  command->add_option("--log", args->log, "CARMEN log (.clf, .log, .gz)")->required();
  command->add_option("--out", args->out, "Output folder for map.yaml/pgm, trajectory.txt")
      ->required();
  command->add_option("--config", args->config, "SLAM options YAML (see config/slam.yaml)")
      ->transform(ShippedFile());
  command->add_option("--particles", args->particles, "Number of particles")
      ->check(CLI::Range(1, 10000));
  command->add_option("--seed", args->seed, "Random seed")->check(CLI::NonNegativeNumber);
  command->add_option("--threads", args->threads, "Worker threads (0 = one per core)")
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--variant", args->variant,
                   "Seed 003 improvements: plain (GMapping), annealing, genetic, both")
      ->check(CLI::IsMember({"plain", "annealing", "genetic", "both"}));
  command
      ->add_option("--every-scan", args->every_scan,
                   "Poses of unprocessed scans: localize (in the final map) or interpolate")
      ->check(CLI::IsMember({"localize", "interpolate"}));
  CLI::Option* pose_graph_on =
      command->add_flag("--pose-graph", args->pose_graph_on,
                        "Loop closures and sparse pose adjustment behind the filter (config "
                        "pose_graph.enabled; on by default)");
  command->add_flag("--no-pose-graph", args->pose_graph_off, "The plain filter (no pose graph)")
      ->excludes(pose_graph_on);
  command->add_option("--depth", args->depth_run,
                      "Run folder whose depth frames are fused into the map (seed 004): "
                      "camera.yaml, detections.jsonl, frames/*_depth.png");
  CLI::Option* semantic =
      command->add_option("--semantic", args->semantic.run,
                          "Run folder whose frames are mapped semantically while SLAM runs "
                          "(camera.yaml, detections.jsonl, frames/): also writes semantic.json, "
                          "keyframes.json, semantic.png and semantic_growth.json");
  command
      ->add_option("--detector", args->semantic.detector.model,
                   "With --semantic: YOLOv8-format ONNX model run on the frames instead of "
                   "RUN/detections.jsonl")
      ->needs(semantic)
      ->transform(ShippedFile());
  command
      ->add_option("--classes", args->semantic.detector.classes, "Class-names file of --detector")
      ->transform(ShippedFile());
  command
      ->add_option("--class-map", args->semantic.detector.class_map,
                   "YAML map 'model class: semchain class' of --detector's classes (e.g. "
                   "config/classes/coco.yaml); the classes it does not name are dropped")
      ->needs("--detector");
  command->add_option(
      "--detector-input", args->semantic.detector.input,
      "Network input WIDTHxHEIGHT of --detector (multiples of 32), or auto: its export size");
  command->add_option("--scale", args->semantic.scale, "Pixels per metre of semantic.png")
      ->check(CLI::Range(1.0, 1000.0));
  command
      ->add_option("--min-detection-score", args->semantic.min_detection_score,
                   kMinDetectionScoreHelp)
      ->needs(semantic)
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  command->add_option("--max-scans", args->max_scans, "Use only the first N scans of the log")
      ->check(CLI::PositiveNumber);
  command->add_flag("--raw-odometry", args->raw_odometry,
                    "Use the log's odometry as written, also where it moves forward while its "
                    "ODOM velocity says the robot backs up (by default such steps are reversed)");
  command->callback([args, &exit_code] { exit_code = RunSlamCommand(*args); });
}

}  // namespace semchain::app
