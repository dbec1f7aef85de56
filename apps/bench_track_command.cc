// semchain bench track (--log LOG | --bag BAG) --out DIR [--config C.yaml] [--methods M1,M2]
//                      [--particles N] [--seed S] [--map MAP]
// Tracking on the map built from the same data: the map and its trajectory come from SLAM on the
// log (as `semchain slam` makes them; a bag is imported first, as `semchain bag import` does),
// then each method's Localizer is given the trajectory's first pose and fed every scan with its
// odometry; each scan's estimate is scored against the map's own pose of that scan. Also checks
// the reference itself (eval::ReferenceCheck). Writes DIR/map/ (map.yaml, map.pgm,
// trajectory.txt), DIR/results.json, DIR/results.md, DIR/trace.csv and DIR/error_<method>.png.
#include <spdlog/spdlog.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "apps/command.h"
#include "apps/track_drawing.h"
#include "apps/track_report.h"
#include "core/atomic_file.h"
#include "core/progress_bar.h"
#include "eval/reference_check.h"
#include "eval/track_benchmark.h"
#include "io/carmen.h"
#include "io/trajectory_io.h"
#include "localization/localizer.h"
#include "mapping/map_io.h"
#include "mapping/slam_options_io.h"
#include "mapping/slam_pipeline.h"
#ifdef SEMCHAIN_WITH_ROS
#include "ros/bag_import.h"
#endif

namespace semchain::app {
namespace {

namespace fs = std::filesystem;

struct BenchTrackArgs {
  std::string log, bag, out, config, map;
  std::vector<std::string> methods = localization::LocalizationMethodNames();
  std::optional<int> particles;
  std::optional<int> max_beams;
  std::optional<double> update_min_d, update_min_a;
  std::string beam_selection;
  bool no_scan_tracking = false;
  std::optional<double> min_score, confident_score, translation_weight, rotation_weight;
  std::optional<double> search_margin;
  std::optional<double> search_min_ratio;
  int seed = 1;
};

// The log to read: --log, or the bag imported into DIR/run.
Result<fs::path> LogPath(const BenchTrackArgs& args) {
  if (args.bag.empty()) return fs::path(args.log);
#ifdef SEMCHAIN_WITH_ROS
  const fs::path run = fs::path(args.out) / "run";
  // Tracking needs the scans and odometry alone (a bag's camera may be uncalibrated).
  ros1::BagImportOptions options;
  options.import_camera = false;
  const Result<ros1::BagImportSummary> imported = ros1::ImportBagToRun(args.bag, run, options);
  if (!imported.ok()) return imported.status();
  for (const std::string& w : imported->warnings) spdlog::warn("bench track: {}", w);
  spdlog::info("bench track: imported {} scans from {} (odometry from {})", imported->scans,
               args.bag, imported->odometry);
  return run / "log.clf";
#else
  return Status::Error("bench track: --bag needs a semchain built with ROS 1 (see `semchain bag`)");
#endif
}

// The map and its trajectory: SLAM on the scans (written to DIR/map), or a map folder given.
struct MapAndReference {
  mapping::MapImage map;
  std::vector<Pose2> reference;
  nlohmann::json info;
};

Result<MapAndReference> BuildMap(const BenchTrackArgs& args,
                                 const std::vector<StampedScan>& scans) {
  MapAndReference out;
  std::vector<StampedPose> trajectory;
  if (!args.map.empty()) {
    Result<mapping::MapImage> map = mapping::ReadMap(fs::path(args.map) / "map.yaml");
    if (!map.ok()) return map.status();
    Result<std::vector<StampedPose>> read = ReadTrajectory(fs::path(args.map) / "trajectory.txt");
    if (!read.ok()) return read.status();
    out.map = std::move(*map);
    trajectory = std::move(*read);
    out.info = {{"from", "map folder " + args.map}};
  } else {
    mapping::SlamOptions options;
    if (!args.config.empty()) {
      SEMCHAIN_RETURN_IF_ERROR(mapping::LoadSlamOptions(args.config, &options));
    }
    std::string error;
    if (!options.Validate(&error)) return Status::Error("invalid SLAM options: " + error);
    ProgressBar bar("bench track: slam", 2 * scans.size());
    const auto start = std::chrono::steady_clock::now();
    mapping::SlamResult slam =
        mapping::RunSlam(scans, options, [&bar](std::size_t done) { bar.Update(done); });
    bar.Finish();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out.map = mapping::GridToMapImage(slam.map);
    trajectory = std::move(slam.trajectory);
    const fs::path dir = fs::path(args.out) / "map";
    SEMCHAIN_RETURN_IF_ERROR(EnsureWritableDirectory(dir));
    SEMCHAIN_RETURN_IF_ERROR(mapping::WriteMap(dir / "map.yaml", out.map));
    SEMCHAIN_RETURN_IF_ERROR(WriteTrajectory(dir / "trajectory.txt", trajectory));
    out.info = {{"from", "SLAM on the same scans" +
                             (args.config.empty() ? std::string() : " (" + args.config + ")")},
                {"processed", slam.statistics.processed},
                {"localized", slam.every_scan.matched},
                {"localized_searched", slam.every_scan.searched},
                {"localized_replaced", slam.every_scan.replaced},
                {"slam_seconds", seconds}};
  }
  if (trajectory.size() != scans.size()) {
    return Status::Error("bench track: the map's trajectory has " +
                         std::to_string(trajectory.size()) + " poses for " +
                         std::to_string(scans.size()) + " scans");
  }
  for (const StampedPose& p : trajectory) out.reference.push_back(p.pose);
  out.info["width"] = out.map.width;
  out.info["height"] = out.map.height;
  out.info["resolution"] = out.map.resolution;
  return out;
}

Result<localization::AmclOptions> TrackerOptions(const BenchTrackArgs& args) {
  localization::AmclOptions amcl;
  if (args.particles) amcl.max_particles = *args.particles;
  amcl.min_particles = std::min(amcl.min_particles, amcl.max_particles);
  if (args.max_beams) amcl.max_beams = *args.max_beams;
  if (args.beam_selection == "evenly") amcl.beam_selection = localization::BeamSelection::kEvenly;
  if (args.beam_selection == "returns") {
    amcl.beam_selection = localization::BeamSelection::kReturns;
  }
  if (args.update_min_d) amcl.update_min_d = *args.update_min_d;
  if (args.update_min_a) amcl.update_min_a = *args.update_min_a;
  std::string error;
  if (!amcl.Validate(&error)) return Status::Error("bench track: AMCL options: " + error);
  return amcl;
}

nlohmann::json AmclJson(const localization::AmclOptions& a) {
  return {{"max_particles", a.max_particles},
          {"min_particles", a.min_particles},
          {"max_beams", a.max_beams},
          {"beam_selection", a.beam_selection == localization::BeamSelection::kReturns
                                 ? "evenly spaced over the returns"
                                 : "evenly spaced"},
          {"update_min_d", a.update_min_d},
          {"update_min_a", a.update_min_a}};
}

Result<std::vector<localization::LocalizationMethod>> ParseMethods(
    const std::vector<std::string>& names) {
  std::vector<localization::LocalizationMethod> methods;
  for (const std::string& name : names) {
    const auto method = localization::ParseLocalizationMethod(name);
    if (!method) {
      return Status::Error("bench track: --methods: unknown method '" + name + "' (" +
                           localization::LocalizationMethodList() + ")");
    }
    methods.push_back(*method);
  }
  return methods;
}

Result<std::vector<StampedScan>> ReadScans(const BenchTrackArgs& args) {
  const Result<fs::path> log_path = LogPath(args);
  if (!log_path.ok()) return log_path.status();
  const Result<carmen::Log> log = carmen::ReadLog(*log_path);
  if (!log.ok()) return log.status();
  // The odometry SLAM sees (`semchain slam` repairs reversed steps the same way).
  mapping::ReversedOdometryRepair repair;
  return mapping::ScansFromLog(*log, log_path->string(), &repair);
}

Status SetScanTracking(const BenchTrackArgs& args, eval::TrackOptions* track_options) {
  track_options->localizer.seed = static_cast<std::uint64_t>(args.seed);
  localization::ScanTrackingOptions& scan_tracking = track_options->localizer.scan_tracking;
  scan_tracking.enabled = !args.no_scan_tracking;
  if (args.min_score) scan_tracking.min_score = *args.min_score;
  if (args.confident_score) scan_tracking.confident_score = *args.confident_score;
  if (args.translation_weight) scan_tracking.translation_weight = *args.translation_weight;
  if (args.rotation_weight) scan_tracking.rotation_weight = *args.rotation_weight;
  if (args.search_margin) scan_tracking.search_margin_ratio = *args.search_margin;
  if (args.search_min_ratio) scan_tracking.search_min_ratio = *args.search_min_ratio;
  std::string error;
  if (!scan_tracking.Validate(&error)) return Status::Error("bench track: " + error);
  return Status::Ok();
}

// The set-up of the benchmark; TrackMethods fills in "methods".
nlohmann::json ResultsJson(const BenchTrackArgs& args, std::size_t scans,
                           const MapAndReference& built, const localization::AmclOptions& amcl,
                           const std::vector<eval::ReferenceCheck>& checks,
                           const TrackTarget& target) {
  return {{"source", args.bag.empty() ? args.log : args.bag},
          {"scans", scans},
          {"map", built.info},
          {"amcl", AmclJson(amcl)},
          {"seed", args.seed},
          {"scan_tracking", !args.no_scan_tracking},
          {"target",
           {{"median_m", target.median_m},
            {"median_deg", target.median_deg},
            {"max_m", target.max_m},
            {"max_deg", target.max_deg}}},
          {"reference", ReferenceJson(checks)},
          {"methods", nlohmann::json::object()}};
}

// Each method over every scan: its summary into results["methods"], its errors drawn into
// DIR/error_<method>.png.
Result<std::vector<MethodTrack>> TrackMethods(
    const BenchTrackArgs& args, const std::vector<localization::LocalizationMethod>& methods,
    const localization::LocalizerMap& map, const std::vector<StampedScan>& scans,
    const std::vector<Pose2>& reference, const eval::TrackOptions& track_options,
    const std::vector<eval::ReferenceCheck>& checks, const TrackTarget& target,
    nlohmann::json* results) {
  std::vector<MethodTrack> tracks;
  for (const localization::LocalizationMethod method : methods) {
    MethodTrack t;
    t.method = localization::LocalizationMethodName(method);
    t.scans = eval::TrackScans(map, method, scans, reference, track_options);
    t.summary = eval::SummarizeTrack(t.scans);
    nlohmann::json& summary = (*results)["methods"][t.method];
    summary = SummaryJson(t.summary, target);
    summary["over_target"] = OverTargetJson(t.scans, checks, target);
    spdlog::info("bench track: {} {}", t.method, summary.dump());
    SEMCHAIN_RETURN_IF_ERROR(WriteTrackPng(
        "bench track " + t.method + ": " + (*results)["source"].get<std::string>(), t.scans, checks,
        target.median_m, target.median_deg, fs::path(args.out) / ("error_" + t.method + ".png")));
    tracks.push_back(std::move(t));
  }
  return tracks;
}

Status WriteResults(const fs::path& out, const std::vector<StampedScan>& scans,
                    const std::vector<Pose2>& reference,
                    const std::vector<eval::ReferenceCheck>& checks,
                    const std::vector<MethodTrack>& tracks, const nlohmann::json& results) {
  std::vector<double> stamps;
  for (const StampedScan& s : scans) stamps.push_back(s.scan.timestamp);
  SEMCHAIN_RETURN_IF_ERROR(
      WriteFileAtomically(out / "trace.csv", TraceCsv(stamps, reference, checks, tracks)));
  SEMCHAIN_RETURN_IF_ERROR(WriteFileAtomically(out / "results.json", results.dump(2) + "\n"));
  return WriteFileAtomically(out / "results.md", TrackMarkdown(results));
}

Status RunBenchTrack(const BenchTrackArgs& args) {
  const Result<std::vector<localization::LocalizationMethod>> methods = ParseMethods(args.methods);
  if (!methods.ok()) return methods.status();
  const Result<localization::AmclOptions> amcl = TrackerOptions(args);
  if (!amcl.ok()) return amcl.status();
  SEMCHAIN_RETURN_IF_ERROR(EnsureWritableDirectory(args.out));
  const Result<std::vector<StampedScan>> scans = ReadScans(args);
  if (!scans.ok()) return scans.status();
  const Result<MapAndReference> built = BuildMap(args, *scans);
  if (!built.ok()) return built.status();

  const localization::LocalizerMap map(built->map, semantic::SemanticMap(), *amcl,
                                       localization::PreLocalizationOptions(),
                                       localization::ScanMatchRelocalizerOptions());
  eval::TrackOptions track_options;
  const std::vector<eval::ReferenceCheck> checks =
      eval::CheckReference(map.matcher, *scans, built->reference,
                           track_options.localizer.scan_tracking.point_spacing_meters);
  SEMCHAIN_RETURN_IF_ERROR(SetScanTracking(args, &track_options));
  const TrackTarget target;
  nlohmann::json results = ResultsJson(args, scans->size(), *built, *amcl, checks, target);
  const Result<std::vector<MethodTrack>> tracks = TrackMethods(
      args, *methods, map, *scans, built->reference, track_options, checks, target, &results);
  if (!tracks.ok()) return tracks.status();
  return WriteResults(fs::path(args.out), *scans, built->reference, checks, *tracks, results);
}

}  // namespace

void AddBenchTrack(CLI::App& bench, int& exit_code) {
  auto args = std::make_shared<BenchTrackArgs>();
  CLI::App* command = bench.add_subcommand(
      "track",
      "Tracking from a known start on the map built from the same data: every scan's estimate "
      "against the map's own trajectory (median, p95, max error; CPU per update)");
  CLI::Option* log = command->add_option("--log", args->log, "CARMEN log (.clf, .log, .gz)");
  CLI::Option* bag =
      command->add_option("--bag", args->bag, "ROS 1 bag, imported as `semchain bag import` does");
  log->excludes(bag);
  command->add_option("--out", args->out, "Output folder")->required();
  command->add_option("--config", args->config, "SLAM options YAML for the map (config/slam.yaml)");
  command->add_option("--map", args->map,
                      "Track on this map folder (map.yaml, trajectory.txt with a pose per scan of "
                      "the log) instead of building one");
  command
      ->add_option(
          "--methods", args->methods,
          "Methods, comma-separated (default: all: " + localization::LocalizationMethodList() + ")")
      ->delimiter(',');
  command->add_option("--particles", args->particles, "AMCL max_particles (default 2000)")
      ->check(CLI::Range(1, 1000000));
  command->add_option("--laser-max-beams", args->max_beams, "AMCL max_beams")
      ->check(CLI::Range(2, 100000));
  command
      ->add_option("--beam-selection", args->beam_selection,
                   "AMCL beam_selection: evenly (nav2: evenly over all beams) or returns (evenly "
                   "over the beams with a return)")
      ->check(CLI::IsMember({"evenly", "returns"}));
  command->add_option("--update-min-d", args->update_min_d, "AMCL update_min_d (m)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--update-min-a", args->update_min_a, "AMCL update_min_a (rad)")
      ->check(CLI::NonNegativeNumber);
  command->add_flag("--no-scan-tracking", args->no_scan_tracking,
                    "Track with AMCL alone (nav2), without matching each scan against the map");
  command->add_option("--match-min-score", args->min_score,
                      "Scan tracking: the least score of a match (0-1, default 0.15; at least "
                      "half the recent matches' typical score)");
  command->add_option("--match-confident-score", args->confident_score,
                      "Scan tracking: a refinement scoring this (0-1, default 0.75; at most 0.9 of "
                      "the recent matches' typical score) is taken without a window search");
  command->add_option("--match-translation-weight", args->translation_weight,
                      "Scan tracking: the prior's translation weight (default 1)");
  command->add_option("--match-rotation-weight", args->rotation_weight,
                      "Scan tracking: the prior's rotation weight (default 3)");
  command->add_option("--match-search-margin", args->search_margin,
                      "Scan tracking: a searched pose replaces the refinement of the prediction "
                      "only when it scores this many times as much (default 1)");
  command->add_option("--match-search-min-ratio", args->search_min_ratio,
                      "Scan tracking: where the prediction's refinement fits, a searched pose "
                      "must score this fraction of the recent matches' typical score (default "
                      "0.8)");
  command->add_option("--seed", args->seed, "Seed of the filters")->capture_default_str();
  command->callback([args, &exit_code] {
    if (args->log.empty() == args->bag.empty()) {
      exit_code = ReportError(Status::Error("bench track: give one of --log or --bag"));
      return;
    }
    const Status status = RunBenchTrack(*args);
    exit_code = status.ok() ? 0 : ReportError(status);
  });
}

}  // namespace semchain::app
