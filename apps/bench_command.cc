// semchain bench slam --log L1.clf [L2.clf ...] --relations R1.relations [R2.relations ...]
//     [--config default,config/slam-gmapping.yaml] [--particles 8,30,50]
//     [--variants plain,annealing,genetic,both] [--seed 1,2,3] --out DIR
// Runs `semchain slam` once per log × configuration × particle count × variant × seed in a child
// process, measuring wall time and the child's peak resident memory (wait4), and scores each
// trajectory with the relation metric (Kümmerle et al. 2009) or, with --perturb-odometry on one
// corrected log, with the ATE against the log's corrected poses (labelled synthetic-odometry).
// Writes DIR/results.json (every run) and DIR/results.md (every run, and a summary over seeds).
#include <fcntl.h>
#include <spdlog/spdlog.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>

#include "apps/command.h"
#include "apps/shipped_file.h"
#include "core/atomic_file.h"
#include "eval/ate.h"
#include "eval/relations.h"
#include "eval/statistics.h"
#include "io/carmen.h"
#include "io/trajectory_io.h"
#include "mapping/odometry_perturbation.h"

namespace semchain::app {
namespace {

struct BenchSlamArgs {
  std::vector<std::string> logs, relations;
  std::string out, every_scan;
  // SLAM option files; "default" runs without one (the built-in defaults).
  std::vector<std::string> configs{"default"};
  std::vector<int> particles{8, 30, 50};
  std::vector<std::string> variants{"plain", "annealing", "genetic", "both"};
  std::vector<int> seeds{1};
  std::optional<int> threads, perturb_seed, max_scans;
};

// One cell of the benchmark grid.
struct RunKey {
  std::size_t log = 0;  // index into BenchSlamArgs::logs
  std::string config;
  int particles = 0;
  std::string variant;
  int seed = 1;
};

// "fr079" for ".../fr079.clf.gz", "slam-gmapping" for "config/slam-gmapping.yaml".
std::string Label(const std::string& path) {
  if (path == "default") return path;
  std::string name = std::filesystem::path(path).filename().string();
  for (const char* suffix : {".gz", ".clf", ".log", ".yaml"}) {
    const std::string s(suffix);
    if (name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0) {
      name.resize(name.size() - s.size());
    }
  }
  return name;
}

struct Reference {  // what the trajectories are scored against
  std::vector<eval::Relation> relations;
  std::vector<StampedPose> truth;
  std::string slam_log;  // the log the runs read (the perturbed copy in ATE mode)
};

struct ChildResult {
  int exit_code = -1;
  double wall_s = 0.0;
  double peak_rss_mb = 0.0;
};

// Runs this binary with 'args', stdout and stderr to 'log_path'; waits with wait4 for its
// resource usage.
ChildResult RunChild(const std::vector<std::string>& args, const std::string& log_path) {
  std::vector<char*> argv;
  static char self[] = "/proc/self/exe";
  argv.push_back(self);
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      ::dup2(fd, STDOUT_FILENO);
      ::dup2(fd, STDERR_FILENO);
    }
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ChildResult result;
  if (pid < 0) return result;
  int status = 0;
  struct rusage usage {};
  ::wait4(pid, &status, 0, &usage);
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.peak_rss_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;  // KiB on Linux
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

std::vector<std::string> SlamArgs(const BenchSlamArgs& args, const Reference& reference,
                                  const std::filesystem::path& dir, const RunKey& key) {
  std::vector<std::string> a = {"slam",
                                "--log",
                                reference.slam_log,
                                "--out",
                                dir.string(),
                                "--particles",
                                std::to_string(key.particles),
                                "--variant",
                                key.variant,
                                "--seed",
                                std::to_string(key.seed)};
  if (key.config != "default") a.insert(a.end(), {"--config", key.config});
  if (args.threads) a.insert(a.end(), {"--threads", std::to_string(*args.threads)});
  if (args.max_scans) a.insert(a.end(), {"--max-scans", std::to_string(*args.max_scans)});
  if (!args.every_scan.empty()) a.insert(a.end(), {"--every-scan", args.every_scan});
  return a;
}

// Scores one run's trajectory.
Result<nlohmann::json> Score(const std::filesystem::path& dir, const Reference& reference) {
  const Result<std::vector<StampedPose>> trajectory = ReadTrajectory(dir / "trajectory.txt");
  if (!trajectory.ok()) return trajectory.status();
  if (!reference.relations.empty()) {
    const Result<eval::RelationErrors> errors =
        eval::EvaluateRelations(*trajectory, reference.relations);
    if (!errors.ok()) return errors.status();
    return nlohmann::json::parse(eval::RelationErrorsToJson(*errors));
  }
  // The run gives a pose for every scan of the perturbed log (its first --max-scans), in the
  // log's order, and the truth is that log's corrected poses: they pair by index, which also
  // scores logs whose timestamps are broken (Killian, FR-campus).
  if (trajectory->size() > reference.truth.size()) {
    return Status::Error("the run has " + std::to_string(trajectory->size()) +
                         " poses for a log of " + std::to_string(reference.truth.size()) +
                         " scans");
  }
  const std::vector<StampedPose> truth(
      reference.truth.begin(),
      reference.truth.begin() + static_cast<std::ptrdiff_t>(trajectory->size()));
  eval::AteOptions by_index;
  by_index.pair_by_index = true;
  const Result<eval::AteResult> ate = eval::EvaluateAte(*trajectory, truth, by_index);
  if (!ate.ok()) return ate.status();
  nlohmann::json json = nlohmann::json::parse(eval::AteResultToJson(*ate));
  eval::AteOptions aligned = by_index;
  aligned.align = true;
  const Result<eval::AteResult> with_alignment = eval::EvaluateAte(*trajectory, truth, aligned);
  if (with_alignment.ok()) json["ate_rmse_aligned_m"] = with_alignment->ate_rmse_m;
  return json;
}

std::string Fixed(double value, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", digits, value);
  return buffer;
}

// The error a run is ranked by: the mean translational relation error, or the ATE RMSE.
double RunError(const nlohmann::json& run, bool relations) {
  return run["metrics"][relations ? "trans_mean_m" : "ate_rmse_m"].get<double>();
}

// Over the seeds of each (log, config, particles, variant): mean ± std of the runs' errors, the
// failures (runs above twice the median error of all runs of that log and configuration), and
// the mean wall time.
nlohmann::json Summary(const nlohmann::json& runs, bool relations) {
  std::map<std::pair<std::string, std::string>, std::vector<double>> by_log_config;
  for (const nlohmann::json& run : runs) {
    if (run.contains("metrics")) {
      by_log_config[{run["log"], run["config"]}].push_back(RunError(run, relations));
    }
  }
  std::map<std::pair<std::string, std::string>, double> medians;
  for (const auto& [key, errors] : by_log_config) {
    medians[key] = eval::Median(errors).value_or(0.0);
  }
  nlohmann::json summary = nlohmann::json::array();
  std::map<std::tuple<std::string, std::string, int, std::string>, std::size_t> rows;
  for (const nlohmann::json& run : runs) {
    const auto key =
        std::make_tuple(run["log"].get<std::string>(), run["config"].get<std::string>(),
                        run["particles"].get<int>(), run["variant"].get<std::string>());
    if (!rows.count(key)) {
      rows[key] = summary.size();
      summary.push_back({{"log", std::get<0>(key)},
                         {"config", std::get<1>(key)},
                         {"particles", std::get<2>(key)},
                         {"variant", std::get<3>(key)},
                         {"runs", 0},
                         {"failed_runs", 0},
                         {"failures", 0},
                         {"errors", nlohmann::json::array()},
                         {"rot_errors", nlohmann::json::array()},
                         {"wall_s", nlohmann::json::array()}});
    }
    nlohmann::json& row = summary[rows[key]];
    row["runs"] = row["runs"].get<int>() + 1;
    row["wall_s"].push_back(run["wall_s"]);
    if (!run.contains("metrics")) {
      row["failed_runs"] = row["failed_runs"].get<int>() + 1;
      continue;
    }
    const double error = RunError(run, relations);
    row["errors"].push_back(error);
    row["rot_errors"].push_back(
        run["metrics"][relations ? "rot_mean_deg" : "rot_rmse_deg"].get<double>());
    if (error > 2.0 * medians[{run["log"], run["config"]}]) {
      row["failures"] = row["failures"].get<int>() + 1;
    }
  }
  for (nlohmann::json& row : summary) {
    const eval::MeanStd error =
        eval::ComputeSampleMeanStd(row["errors"].get<std::vector<double>>());
    const eval::MeanStd rot =
        eval::ComputeSampleMeanStd(row["rot_errors"].get<std::vector<double>>());
    row["error_mean"] = error.mean;
    row["error_std"] = error.std;
    row["rot_mean"] = rot.mean;
    row["rot_std"] = rot.std;
    row["wall_s_mean"] = eval::ComputeMeanStd(row["wall_s"].get<std::vector<double>>()).mean;
  }
  return summary;
}

std::string MarkdownTable(const nlohmann::json& results, bool relations) {
  std::ostringstream md;
  md << "# semchain bench slam\n\n"
     << (relations ? "metric: relation error (Kümmerle et al. 2009)"
                   : "metric: ATE against the corrected poses (synthetic-odometry)")
     << "\n\n## Summary over seeds\n\n"
     << "failures: runs above twice the median error of all runs of the same log and "
        "configuration\n\n"
     << "| log | config | particles | variant | runs | "
     << (relations ? "trans (m) mean ± std over seeds | rot (deg) mean"
                   : "ATE RMSE (m) mean ± std over seeds | rot RMSE (deg) mean")
     << " | failures | wall (s) |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const nlohmann::json& row : results["summary"]) {
    md << "| " << row["log"].get<std::string>() << " | " << row["config"].get<std::string>()
       << " | " << row["particles"] << " | " << row["variant"].get<std::string>() << " | "
       << row["runs"] << " | " << Fixed(row["error_mean"], 4) << " ± " << Fixed(row["error_std"], 4)
       << " | " << Fixed(row["rot_mean"], 3) << " | " << row["failures"];
    if (row["failed_runs"].get<int>() > 0) md << " (+" << row["failed_runs"] << " crashed)";
    md << " | " << Fixed(row["wall_s_mean"], 1) << " |\n";
  }
  md << "\n## Every run\n\n";
  if (relations) {
    md << "| log | config | particles | variant | seed | trans (m) mean ± std | rot (deg) mean ± "
          "std | wall (s) | peak RSS (MB) | resamplings / genetic | recoveries | loop closures "
          "found / accepted / rejected / gated | optimizer (s) |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  } else {
    md << "| log | config | particles | variant | seed | ATE RMSE (m) | ATE RMSE aligned (m) | "
          "ATE max (m) | rot RMSE (deg) | wall (s) | peak RSS (MB) | loop closures found / "
          "accepted / rejected / gated | optimizer (s) |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  }
  for (const nlohmann::json& run : results["runs"]) {
    md << "| " << run["log"].get<std::string>() << " | " << run["config"].get<std::string>()
       << " | " << run["particles"] << " | " << run["variant"].get<std::string>() << " | "
       << run["seed"] << " | ";
    if (!run.contains("metrics")) {
      md << "failed: " << run.value("error", std::string("?")) << " |\n";
      continue;
    }
    const nlohmann::json& m = run["metrics"];
    if (relations) {
      md << Fixed(m["trans_mean_m"], 4) << " ± " << Fixed(m["trans_std_m"], 4) << " | "
         << Fixed(m["rot_mean_deg"], 3) << " ± " << Fixed(m["rot_std_deg"], 3) << " | ";
    } else {
      md << Fixed(m["ate_rmse_m"], 4) << " | " << Fixed(m.value("ate_rmse_aligned_m", -1.0), 4)
         << " | " << Fixed(m["ate_max_m"], 4) << " | " << Fixed(m["rot_rmse_deg"], 3) << " | ";
    }
    md << Fixed(run["wall_s"], 1) << " | " << Fixed(run["peak_rss_mb"], 0);
    if (relations) {
      md << " | " << run.value("resamplings", 0) << " / " << run.value("genetic_resamplings", 0)
         << " | " << run.value("recoveries", 0);
    }
    md << " | ";
    if (run.contains("pose_graph")) {
      const nlohmann::json& g = run["pose_graph"];
      md << g["closures_found"] << " / " << g["closures_accepted"] << " / "
         << g["closures_rejected"] << " / " << g.value("closures_gated", 0) << " | "
         << Fixed(g["optimizer_seconds"], 2);
    } else {
      md << "– | –";
    }
    md << " |\n";
  }
  return md.str();
}

nlohmann::json RunOne(const BenchSlamArgs& args, const Reference& reference, const RunKey& key) {
  const std::string log = Label(args.logs[key.log]);
  const std::filesystem::path dir =
      std::filesystem::path(args.out) / "runs" / log / Label(key.config) /
      ("p" + std::to_string(key.particles) + "_" + key.variant + "_s" + std::to_string(key.seed));
  std::filesystem::create_directories(dir);
  const ChildResult child =
      RunChild(SlamArgs(args, reference, dir, key), (dir / "slam.log").string());
  nlohmann::json run = {{"log", log},
                        {"log_path", args.logs[key.log]},
                        {"config", Label(key.config)},
                        {"config_path", key.config},
                        {"particles", key.particles},
                        {"variant", key.variant},
                        {"seed", key.seed},
                        {"wall_s", child.wall_s},
                        {"peak_rss_mb", child.peak_rss_mb},
                        {"exit_code", child.exit_code},
                        {"output", dir.string()}};
  if (child.exit_code != 0) {
    run["error"] = "slam exited with " + std::to_string(child.exit_code) + " (see slam.log)";
    return run;
  }
  const Result<nlohmann::json> metrics = Score(dir, reference);
  if (!metrics.ok()) {
    run["error"] = metrics.status().message();
    return run;
  }
  run["metrics"] = *metrics;
  const Result<std::string> stats = ReadFile(dir / "slam.json");
  if (stats.ok()) {
    const nlohmann::json s = nlohmann::json::parse(*stats, nullptr, false);
    for (const char* key_name :
         {"processed", "resamplings", "genetic_resamplings", "crossovers", "mutations",
          "mean_effective_sample_size", "mean_alpha", "recoveries", "unmatched_updates"}) {
      if (s.is_object() && s.contains(key_name)) run[key_name] = s[key_name];
    }
    if (s.is_object() && s.contains("pose_graph")) run["pose_graph"] = s["pose_graph"];
  }
  return run;
}

Result<Reference> PrepareReference(const BenchSlamArgs& args, std::size_t index) {
  Reference reference;
  const std::string& log_path = args.logs[index];
  reference.slam_log = log_path;
  if (!args.relations.empty()) {
    Result<std::vector<eval::Relation>> relations = eval::ReadRelations(args.relations[index]);
    if (!relations.ok()) return relations.status();
    reference.relations = std::move(*relations);
  }
  const Result<carmen::Log> log = carmen::ReadLog(log_path);
  if (!log.ok()) return log.status();
  if (log->Lasers().empty()) return Status::Error(log_path + ": no laser scans in the log");
  if (!args.perturb_seed) return reference;
  mapping::OdometryPerturbationOptions options;
  options.seed = static_cast<std::uint64_t>(*args.perturb_seed);
  mapping::PerturbedLog perturbed = mapping::PerturbOdometry(*log, options);
  SEMCHAIN_RETURN_IF_ERROR(EnsureWritableDirectory(args.out));
  reference.slam_log = (std::filesystem::path(args.out) / "synthetic-odometry.clf").string();
  SEMCHAIN_RETURN_IF_ERROR(carmen::WriteLog(reference.slam_log, perturbed.log));
  SEMCHAIN_RETURN_IF_ERROR(
      WriteTrajectory(std::filesystem::path(args.out) / "truth.txt", perturbed.truth));
  reference.truth = std::move(perturbed.truth);
  return reference;
}

Status CheckArgs(const BenchSlamArgs& args) {
  if (args.relations.empty() == !args.perturb_seed) {
    return Status::Error(
        "bench slam: give either --relations (real odometry) or --perturb-odometry SEED "
        "(a corrected log scored by ATE)");
  }
  if (!args.relations.empty() && args.relations.size() != args.logs.size()) {
    return Status::Error("bench slam: " + std::to_string(args.logs.size()) + " logs but " +
                         std::to_string(args.relations.size()) +
                         " relation files (one per log, in the same order)");
  }
  if (args.perturb_seed && args.logs.size() != 1) {
    return Status::Error("bench slam: --perturb-odometry takes exactly one log");
  }
  std::set<std::string> labels;
  for (const std::string& log : args.logs) {
    if (!labels.insert(Label(log)).second) {
      return Status::Error("bench slam: two logs named '" + Label(log) + "'; rename one");
    }
  }
  for (const std::string& config : args.configs) {
    if (config != "default" && !std::filesystem::is_regular_file(config)) {
      return Status::Error("bench slam: --config " + config + ": no such file");
    }
  }
  return Status::Ok();
}

int RunBenchSlam(const BenchSlamArgs& args) {
  const Status valid = CheckArgs(args);
  if (!valid.ok()) return ReportError(valid);
  const Status writable = EnsureWritableDirectory(args.out);
  if (!writable.ok()) return ReportError(writable);
  std::vector<Reference> references;
  for (std::size_t i = 0; i < args.logs.size(); ++i) {
    Result<Reference> reference = PrepareReference(args, i);
    if (!reference.ok()) return ReportError(reference.status());
    references.push_back(std::move(*reference));
  }
  const bool relations = !args.relations.empty();
  nlohmann::json results = {
      {"logs", args.logs},       {"relations", args.relations},
      {"configs", args.configs}, {"metric", relations ? "relations" : "ate (synthetic-odometry)"},
      {"seeds", args.seeds},     {"runs", nlohmann::json::array()}};
  if (args.perturb_seed) results["perturb_odometry_seed"] = *args.perturb_seed;
  const std::filesystem::path out(args.out);
  const std::size_t total = args.logs.size() * args.configs.size() * args.particles.size() *
                            args.variants.size() * args.seeds.size();
  int failures = 0;
  for (std::size_t log = 0; log < args.logs.size(); ++log) {
    for (const std::string& config : args.configs) {
      for (const int particles : args.particles) {
        for (const std::string& variant : args.variants) {
          for (const int seed : args.seeds) {
            const RunKey key{log, config, particles, variant, seed};
            spdlog::info("bench slam: run {}/{}: {}, {}, {} particles, {}, seed {}",
                         results["runs"].size() + 1, total, Label(args.logs[log]), Label(config),
                         particles, variant, seed);
            results["runs"].push_back(RunOne(args, references[log], key));
            if (!results["runs"].back().contains("metrics")) ++failures;
            results["summary"] = Summary(results["runs"], relations);
            const Status written =
                WriteFileAtomically(out / "results.json", results.dump(2) + "\n");
            if (!written.ok()) return ReportError(written);
            const Status md =
                WriteFileAtomically(out / "results.md", MarkdownTable(results, relations));
            if (!md.ok()) return ReportError(md);
          }
        }
      }
    }
  }
  if (failures > 0) {
    return ReportError(Status::Error("bench slam: " + std::to_string(failures) +
                                     " run(s) failed; see " + (out / "results.md").string()));
  }
  return 0;
}

void AddBenchSlam(CLI::App& bench, int& exit_code) {
  auto args = std::make_shared<BenchSlamArgs>();
  CLI::App* command = bench.add_subcommand(
      "slam",
      "SLAM accuracy, time and memory over logs, configurations, particle counts, seed 003 "
      "variants and seeds");
  command->add_option("--log", args->logs, "CARMEN logs (several: one run grid per log)")
      ->required()
      ->delimiter(',');
  command
      ->add_option("--relations", args->relations,
                   "Kümmerle relations files, one per --log in the same order")
      ->delimiter(',');
  command->add_option("--perturb-odometry", args->perturb_seed,
                      "Corrected log: replace its odometry by seeded synthetic odometry and "
                      "score by ATE against the corrected poses");
  command->add_option("--out", args->out, "Output folder (results.json, results.md, runs/)")
      ->required();
  command->add_option("--particles", args->particles, "Particle counts")->delimiter(',');
  command->add_option("--variants", args->variants, "plain, annealing, genetic, both")
      ->delimiter(',')
      ->check(CLI::IsMember({"plain", "annealing", "genetic", "both"}));
  command
      ->add_option("--config", args->configs,
                   "SLAM option files, each a configuration of the grid; 'default' = the "
                   "built-in defaults (default: default)")
      ->delimiter(',')
      ->transform(ShippedFile());
  command->add_option("--seed", args->seeds, "Random seeds (each configuration runs every one)")
      ->delimiter(',');
  command->add_option("--threads", args->threads, "Worker threads per run");
  command->add_option("--max-scans", args->max_scans, "Use only the first N scans");
  command->add_option("--every-scan", args->every_scan, "localize or interpolate");
  command->callback([args, &exit_code] { exit_code = RunBenchSlam(*args); });
}

}  // namespace

void AddBenchCommand(CLI::App& app, int& exit_code) {
  CLI::App* bench = app.add_subcommand(
      "bench",
      "Benchmarks: slam, closures, localize (real logs), reloc (simulated relocalization trials)");
  bench->require_subcommand(1);
  AddBenchSlam(*bench, exit_code);
  AddBenchClosures(*bench, exit_code);
  AddBenchLocalize(*bench, exit_code);
  AddBenchReloc(*bench, exit_code);
  AddBenchDetector(*bench, exit_code);
  AddBenchTrack(*bench, exit_code);
}

}  // namespace semchain::app
