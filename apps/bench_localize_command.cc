// semchain bench localize --log CORRECTED.clf --trials N --seed S --out DIR
//     [--method amcl|scanmatch-global[,...]] [--protocol semchain|nav2] [--window SECONDS]
//     [--filter-seed F]
// Global localization (unknown start) on a real log with corrected poses: the map is built from
// the corrected poses, each trial starts at a random scan and runs the method over the following
// scans (DESIGN.md §6). --protocol semchain (default): the log's odometry, nav2's AMCL defaults
// (AmclOptions), success = within tolerance to the trial's end. --protocol nav2: the peer's
// set-up (eval::Nav2Protocol). Writes DIR/map.yaml (+ map.pgm), DIR/results.json and
// DIR/results.md.
#include <spdlog/spdlog.h>

#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/command.h"
#include "core/atomic_file.h"
#include "core/progress_bar.h"
#include "eval/log_localization_trials.h"
#include "io/carmen.h"
#include "localization/localization_map.h"
#include "mapping/odometry_perturbation.h"
#include "mapping/slam_pipeline.h"

namespace semchain::app {
namespace {

struct BenchLocalizeArgs {
  std::string log, out;
  std::vector<std::string> methods{"amcl"};
  std::string protocol = "semchain";
  int trials = 20;
  int seed = 1;
  std::optional<int> filter_seed;
  std::optional<double> window_s;
  std::optional<double> alpha;
  std::string resampling = "multinomial";
};

nlohmann::json OptionalNumber(const std::optional<double>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

nlohmann::json TrialJson(const eval::LogTrial& t) {
  return {{"trial", t.trial},
          {"start_scan", t.start_scan},
          {"success", t.success},
          {"time_s", OptionalNumber(t.time_s)},
          {"streak_start_time_s", OptionalNumber(t.streak_start_time_s)},
          {"scans", t.scans_to_converge},
          {"distance_m", t.distance_m},
          {"iterations", t.iterations},
          {"updates", t.updates},
          {"cpu_ms", t.cpu_ms},
          {"estimated", t.estimated},
          {"error_m", t.error_m},
          {"error_deg", t.error_deg},
          {"reached", t.reached},
          {"reach_time_s", OptionalNumber(t.reach_time_s)},
          {"final_within", t.final_within}};
}

nlohmann::json SummaryJson(const eval::LogTrialSummary& s) {
  return {{"trials", s.trials},
          {"successes", s.successes},
          {"success_rate", s.success_rate},
          {"mean_time_s", OptionalNumber(s.mean_time_s)},
          {"median_time_s", OptionalNumber(s.median_time_s)},
          {"mean_streak_start_time_s", OptionalNumber(s.mean_streak_start_time_s)},
          {"median_streak_start_time_s", OptionalNumber(s.median_streak_start_time_s)},
          {"mean_scans", s.mean_scans},
          {"mean_distance_m", s.mean_distance_m},
          {"mean_cpu_ms", s.mean_cpu_ms},
          {"cpu_ms_per_update", s.cpu_ms_per_update},
          {"mean_iterations", s.mean_iterations},
          {"mean_error_m", s.mean_error_m},
          {"mean_error_deg", s.mean_error_deg},
          {"reached", s.reached},
          {"mean_reach_time_s", OptionalNumber(s.mean_reach_time_s)},
          {"final_within", s.final_within}};
}

std::string Fixed(const nlohmann::json& value, int digits) {
  if (value.is_null()) return "n/a";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", digits, value.get<double>());
  return buffer;
}

std::string SuccessRule(const nlohmann::json& results) {
  if (results["protocol"] == "nav2") {
    return "success: the best cluster within 0.25 m and 10° of the corrected pose for 5 "
           "consecutive filter updates (the trial ends there; time: to the update completing the "
           "streak, streak start: to its first update; scanmatch-global: its one accepted "
           "match)";
  }
  return "success: within 0.25 m and 10° of the corrected pose and staying there until the "
         "trial ends";
}

std::string MarkdownTable(const nlohmann::json& results) {
  std::ostringstream md;
  md << "# semchain bench localize\n\nlog: `" << results["log"].get<std::string>() << "`, protocol "
     << results["protocol"].get<std::string>() << ", " << results["trials"] << " trials, seed "
     << results["seed"]
     << (results["filter_seed"].is_null()
             ? std::string()
             : ", filter seed " + std::to_string(results["filter_seed"].get<int>()))
     << ", window " << results["window"].get<std::string>() << ", AMCL alphas " << results["alpha"]
     << ", particles " << results["max_particles"] << "; " << SuccessRule(results)
     << " (reached: within them at least once; at end: within them at the end)\n\n"
     << "| method | successes | success rate | mean time (s) | median time (s) | "
        "mean / median streak start (s) | mean scans | "
        "mean distance (m) | mean iterations | mean CPU (ms) | CPU per update (ms) | "
        "mean error (m) | mean error (deg) | reached | mean time to reach (s) | at end |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [method, m] : results["methods"].items()) {
    md << "| " << method << " | " << m["successes"] << "/" << m["trials"] << " | "
       << Fixed(m["success_rate"], 2) << " | " << Fixed(m["mean_time_s"], 1) << " | "
       << Fixed(m["median_time_s"], 1) << " | " << Fixed(m["mean_streak_start_time_s"], 1) << " / "
       << Fixed(m["median_streak_start_time_s"], 1) << " | " << Fixed(m["mean_scans"], 0) << " | "
       << Fixed(m["mean_distance_m"], 1) << " | " << Fixed(m["mean_iterations"], 1) << " | "
       << Fixed(m["mean_cpu_ms"], 0) << " | " << Fixed(m["cpu_ms_per_update"], 2) << " | "
       << Fixed(m["mean_error_m"], 3) << " | " << Fixed(m["mean_error_deg"], 2) << " | "
       << m["reached"] << " | " << Fixed(m["mean_reach_time_s"], 1) << " | " << m["final_within"]
       << " |\n";
  }
  // Every trial: whether it succeeded and whether the estimate was ever within tolerance.
  for (const auto& [method, runs] : results["runs"].items()) {
    md << "\n## " << method << ", per trial\n\n"
       << "| trial | start scan | success | time (s) | ever within | first within (s) | "
          "updates | CPU (ms) |\n|---|---|---|---|---|---|---|---|\n";
    for (const nlohmann::json& t : runs) {
      md << "| " << t["trial"] << " | " << t["start_scan"] << " | "
         << (t["success"].get<bool>() ? "yes" : "no") << " | " << Fixed(t["time_s"], 1) << " | "
         << (t["reached"].get<bool>() ? "yes" : "no") << " | " << Fixed(t["reach_time_s"], 1)
         << " | " << t["updates"] << " | " << Fixed(t["cpu_ms"], 0) << " |\n";
    }
  }
  return md.str();
}

// The protocol's set-up with the options given over it, checked for every method.
Result<eval::LogTrialOptions> BuildTrialOptions(const BenchLocalizeArgs& args) {
  eval::LogTrialOptions options;
  options.trials = args.trials;
  options.seed = static_cast<std::uint64_t>(args.seed);
  if (args.filter_seed) options.filter_seed = static_cast<std::uint64_t>(*args.filter_seed);
  if (args.protocol == "nav2") {
    if (args.window_s || args.alpha) {
      return Status::Error(
          "bench localize: --window and --alpha are fixed by --protocol nav2 (60 s, 0.2)");
    }
    options = eval::Nav2Protocol(options);
  } else if (args.protocol == "semchain") {
    if (args.window_s) options.window_seconds = *args.window_s;
    if (args.alpha) {
      options.amcl.alpha1 = options.amcl.alpha2 = options.amcl.alpha3 = options.amcl.alpha4 =
          *args.alpha;
    }
  } else {
    return Status::Error("bench localize: --protocol must be semchain or nav2, not '" +
                         args.protocol + "'");
  }
  // How AMCL resamples is the filter's own choice, not a parameter the peer's set-up fixes.
  options.amcl.systematic_resampling = args.resampling == "systematic";
  std::string error;
  for (const std::string& method : args.methods) {
    options.method = method;
    if (!options.Validate(&error)) return Status::Error("bench localize: " + error);
  }
  return options;
}

// The corrected scans (the map and the truth) and, under the nav2 protocol, the scans the
// methods see instead: odometry rebuilt from the corrected poses with seeded noise.
struct TrialScans {
  std::vector<StampedScan> corrected;
  std::vector<StampedScan> perturbed;
  std::vector<Pose2> truth;
};

Result<TrialScans> ReadTrialScans(const BenchLocalizeArgs& args,
                                  const eval::LogTrialOptions& options) {
  const Result<carmen::Log> log = carmen::ReadLog(args.log);
  if (!log.ok()) return log.status();
  Result<std::vector<StampedScan>> scans = mapping::ScansFromLog(*log, args.log);
  if (!scans.ok()) return scans.status();
  TrialScans out;
  out.corrected = std::move(*scans);
  if (options.perturb_odometry) {
    const mapping::PerturbedLog perturbed = mapping::PerturbOdometry(*log, options.odometry_noise);
    Result<std::vector<StampedScan>> noisy = mapping::ScansFromLog(perturbed.log, args.log);
    if (!noisy.ok()) return noisy.status();
    out.perturbed = std::move(*noisy);
    for (const StampedScan& s : out.corrected) out.truth.push_back(s.odometry);
  }
  return out;
}

Result<mapping::MapImage> BuildMap(const BenchLocalizeArgs& args,
                                   const eval::LogTrialOptions& options,
                                   const std::vector<StampedScan>& scans) {
  spdlog::info("bench localize: building the map from {} corrected poses", scans.size());
  mapping::MapImage map =
      eval::MapFromCorrectedPoses(scans, options.map_resolution, options.map_max_range_meters);
  const localization::LocalizationMap check(map, options.amcl.laser_likelihood_max_dist);
  if (check.free_cells().empty()) {
    return Status::Error(args.log + ": the map built from the log has no free cells");
  }
  return map;
}

// Whether the trials can be timed; without timestamps they span a number of scans.
bool CheckTimestamps(const BenchLocalizeArgs& args, const eval::LogTrialOptions& options,
                     const std::vector<StampedScan>& scans) {
  const bool timed = eval::TimestampsUsable(scans);
  if (!timed) {
    spdlog::warn("bench localize: {} has no usable timestamps; trials span {} scans, no times",
                 args.log, options.window_scans);
  }
  return timed;
}

// The set-up of the benchmark; RunMethods fills in "methods" and "runs".
nlohmann::json ResultsJson(const BenchLocalizeArgs& args, const eval::LogTrialOptions& options,
                           const mapping::MapImage& map, bool timed) {
  return {{"log", args.log},
          {"trials", args.trials},
          {"seed", args.seed},
          {"filter_seed",
           args.filter_seed ? nlohmann::json(*args.filter_seed) : nlohmann::json(nullptr)},
          {"protocol", args.protocol},
          {"timestamps_usable", timed},
          {"alpha", options.amcl.alpha1},
          {"max_particles", options.amcl.max_particles},
          {"resampling", args.resampling},
          {"window", timed ? Fixed(options.window_seconds, 0) + " s"
                           : std::to_string(options.window_scans) + " scans"},
          {"map", {{"width", map.width}, {"height", map.height}, {"resolution", map.resolution}}},
          {"methods", nlohmann::json::object()},
          {"runs", nlohmann::json::object()}};
}

void RunMethods(const BenchLocalizeArgs& args, eval::LogTrialOptions options,
                const TrialScans& scans, const mapping::MapImage& map, nlohmann::json* results) {
  const std::vector<StampedScan>& trial_scans =
      options.perturb_odometry ? scans.perturbed : scans.corrected;
  for (const std::string& method : args.methods) {
    options.method = method;
    ProgressBar bar("bench localize " + method, static_cast<std::size_t>(args.trials));
    const std::vector<eval::LogTrial> trials = eval::RunLogTrials(
        trial_scans, map, options, [&bar](int done) { bar.Update(static_cast<std::size_t>(done)); },
        scans.truth);
    bar.Finish();
    nlohmann::json runs = nlohmann::json::array();
    for (const eval::LogTrial& t : trials) runs.push_back(TrialJson(t));
    (*results)["runs"][method] = runs;
    (*results)["methods"][method] = SummaryJson(eval::Summarize(trials));
    spdlog::info("bench localize: {} {}", method, (*results)["methods"][method].dump());
  }
}

int RunBenchLocalize(const BenchLocalizeArgs& args) {
  const Result<eval::LogTrialOptions> options = BuildTrialOptions(args);
  if (!options.ok()) return ReportError(options.status());
  const Result<TrialScans> scans = ReadTrialScans(args, *options);
  if (!scans.ok()) return ReportError(scans.status());
  const Result<mapping::MapImage> map = BuildMap(args, *options, scans->corrected);
  if (!map.ok()) return ReportError(map.status());
  const Status writable = EnsureWritableDirectory(args.out);
  if (!writable.ok()) return ReportError(writable);
  const std::filesystem::path out(args.out);

  const Status map_written = mapping::WriteMap(out / "map.yaml", *map);
  if (!map_written.ok()) return ReportError(map_written);
  const bool timed = CheckTimestamps(args, *options, scans->corrected);
  nlohmann::json results = ResultsJson(args, *options, *map, timed);
  RunMethods(args, *options, *scans, *map, &results);
  const Status json = WriteFileAtomically(out / "results.json", results.dump(2) + "\n");
  if (!json.ok()) return ReportError(json);
  const Status md = WriteFileAtomically(out / "results.md", MarkdownTable(results));
  if (!md.ok()) return ReportError(md);
  return 0;
}

}  // namespace

void AddBenchLocalize(CLI::App& bench, int& exit_code) {
  auto args = std::make_shared<BenchLocalizeArgs>();
  CLI::App* command = bench.add_subcommand(
      "localize", "Global localization trials on a corrected real log (AMCL, scan matching)");
  command->add_option("--log", args->log, "CARMEN log with corrected poses")->required();
  command->add_option("--out", args->out, "Output folder (map, results.json, results.md)")
      ->required();
  command->add_option("--trials", args->trials, "Number of trials")->check(CLI::PositiveNumber);
  command->add_option("--seed", args->seed, "Random seed (trial starts and filters)");
  command
      ->add_option("--filter-seed", args->filter_seed,
                   "Seed of the filters' random streams only (default: --seed); the trial starts "
                   "and the odometry noise keep --seed")
      ->check(CLI::Range(0, std::numeric_limits<int>::max()));
  command->add_option("--method", args->methods, "amcl, scanmatch-global (comma-separated)")
      ->delimiter(',')
      ->check(CLI::IsMember({"amcl", "scanmatch-global"}));
  command->add_option("--protocol", args->protocol,
                      "semchain (default: the log's odometry, within tolerance to the end) or "
                      "nav2 (the peer's set-up: noisy odometry, 20000 particles, 5 updates "
                      "within tolerance, 60 s)");
  command->add_option("--window", args->window_s, "Log seconds per trial (semchain protocol)")
      ->check(CLI::PositiveNumber);
  command
      ->add_option("--alpha", args->alpha,
                   "Set AMCL alpha1..alpha4 (default nav2's 0.2, meant for wheel odometry)")
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--resampling", args->resampling,
                   "AMCL resampling: multinomial (default, nav2's independent draws) or "
                   "systematic (one comb of evenly spaced draws, lower variance)")
      ->check(CLI::IsMember({"multinomial", "systematic"}));
  command->callback([args, &exit_code] { exit_code = RunBenchLocalize(*args); });
}

}  // namespace semchain::app
