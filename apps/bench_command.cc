// semchain bench slam --log L.clf --relations R.relations [--particles 8,30,50]
//     [--variants plain,annealing,genetic,both] --out DIR
// Runs `semchain slam` once per (particle count, variant) in a child process, measuring wall
// time and the child's peak resident memory (wait4), and scores each trajectory with the
// relation metric (Kümmerle et al. 2009) or, with --perturb-odometry on a corrected log, with
// the ATE against the log's corrected poses (labelled synthetic-odometry). Writes
// DIR/results.json and DIR/results.md. (`bench reloc` will be a sibling subcommand.)
#include <fcntl.h>
#include <spdlog/spdlog.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "apps/command.h"
#include "core/atomic_file.h"
#include "eval/ate.h"
#include "eval/relations.h"
#include "io/carmen.h"
#include "io/trajectory_io.h"
#include "mapping/odometry_perturbation.h"

namespace semchain::app {
namespace {

struct BenchSlamArgs {
  std::string log, relations, out, config, every_scan;
  std::vector<int> particles{8, 30, 50};
  std::vector<std::string> variants{"plain", "annealing", "genetic", "both"};
  int seed = 1;
  std::optional<int> threads, perturb_seed, max_scans;
};

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
                                  const std::filesystem::path& dir, int particles,
                                  const std::string& variant) {
  std::vector<std::string> a = {"slam",       "--log",       reference.slam_log,        "--out",
                                dir.string(), "--particles", std::to_string(particles), "--variant",
                                variant,      "--seed",      std::to_string(args.seed)};
  if (!args.config.empty()) a.insert(a.end(), {"--config", args.config});
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
  const Result<eval::AteResult> ate = eval::EvaluateAte(*trajectory, reference.truth);
  if (!ate.ok()) return ate.status();
  nlohmann::json json = nlohmann::json::parse(eval::AteResultToJson(*ate));
  eval::AteOptions aligned;
  aligned.align = true;
  const Result<eval::AteResult> with_alignment =
      eval::EvaluateAte(*trajectory, reference.truth, aligned);
  if (with_alignment.ok()) json["ate_rmse_aligned_m"] = with_alignment->ate_rmse_m;
  return json;
}

std::string Fixed(double value, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", digits, value);
  return buffer;
}

std::string MarkdownTable(const nlohmann::json& results, bool relations) {
  std::ostringstream md;
  md << "# semchain bench slam\n\nlog: `" << results["log"].get<std::string>() << "`  \n"
     << (relations ? "metric: relation error (Kümmerle et al. 2009)"
                   : "metric: ATE against the corrected poses (synthetic-odometry)")
     << ", seed " << results["seed"] << "\n\n";
  if (relations) {
    md << "| particles | variant | trans (m) mean ± std | rot (deg) mean ± std | wall (s) | "
          "peak RSS (MB) | resamplings / genetic |\n|---|---|---|---|---|---|---|\n";
  } else {
    md << "| particles | variant | ATE RMSE (m) | ATE RMSE aligned (m) | ATE max (m) | "
          "rot RMSE (deg) | wall (s) | peak RSS (MB) |\n|---|---|---|---|---|---|---|---|\n";
  }
  for (const nlohmann::json& run : results["runs"]) {
    md << "| " << run["particles"] << " | " << run["variant"].get<std::string>() << " | ";
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
      md << " | " << run.value("resamplings", 0) << " / " << run.value("genetic_resamplings", 0);
    }
    md << " |\n";
  }
  return md.str();
}

nlohmann::json RunOne(const BenchSlamArgs& args, const Reference& reference, int particles,
                      const std::string& variant) {
  const std::filesystem::path dir =
      std::filesystem::path(args.out) / "runs" / ("p" + std::to_string(particles) + "_" + variant);
  std::filesystem::create_directories(dir);
  const ChildResult child =
      RunChild(SlamArgs(args, reference, dir, particles, variant), (dir / "slam.log").string());
  nlohmann::json run = {{"particles", particles},       {"variant", variant},
                        {"wall_s", child.wall_s},       {"peak_rss_mb", child.peak_rss_mb},
                        {"exit_code", child.exit_code}, {"output", dir.string()}};
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
    for (const char* key : {"processed", "resamplings", "genetic_resamplings", "crossovers",
                            "mutations", "mean_effective_sample_size", "mean_alpha"}) {
      if (s.is_object() && s.contains(key)) run[key] = s[key];
    }
  }
  return run;
}

Result<Reference> PrepareReference(const BenchSlamArgs& args) {
  Reference reference;
  reference.slam_log = args.log;
  if (!args.relations.empty()) {
    Result<std::vector<eval::Relation>> relations = eval::ReadRelations(args.relations);
    if (!relations.ok()) return relations.status();
    reference.relations = std::move(*relations);
  }
  const Result<carmen::Log> log = carmen::ReadLog(args.log);
  if (!log.ok()) return log.status();
  if (log->Lasers().empty()) return Status::Error(args.log + ": no laser scans in the log");
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

int RunBenchSlam(const BenchSlamArgs& args) {
  if (args.relations.empty() == !args.perturb_seed) {
    return ReportError(Status::Error(
        "bench slam: give either --relations (real odometry) or --perturb-odometry SEED "
        "(a corrected log scored by ATE)"));
  }
  if (args.perturb_seed) {  // the perturbed log is written there, so check first
    const Status writable = EnsureWritableDirectory(args.out);
    if (!writable.ok()) return ReportError(writable);
  }
  const Result<Reference> reference = PrepareReference(args);
  if (!reference.ok()) return ReportError(reference.status());
  const Status writable = EnsureWritableDirectory(args.out);
  if (!writable.ok()) return ReportError(writable);
  nlohmann::json results = {
      {"log", args.log},
      {"relations", args.relations},
      {"metric", args.relations.empty() ? "ate (synthetic-odometry)" : "relations"},
      {"seed", args.seed},
      {"runs", nlohmann::json::array()}};
  if (args.perturb_seed) results["perturb_odometry_seed"] = *args.perturb_seed;
  const std::filesystem::path out(args.out);
  int failures = 0;
  for (const int particles : args.particles) {
    for (const std::string& variant : args.variants) {
      spdlog::info("bench slam: {} particles, {}", particles, variant);
      results["runs"].push_back(RunOne(args, *reference, particles, variant));
      if (!results["runs"].back().contains("metrics")) ++failures;
      spdlog::info("bench slam: {}", results["runs"].back().dump());
      const Status written = WriteFileAtomically(out / "results.json", results.dump(2) + "\n");
      if (!written.ok()) return ReportError(written);
      const Status md =
          WriteFileAtomically(out / "results.md", MarkdownTable(results, !args.relations.empty()));
      if (!md.ok()) return ReportError(md);
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
      "slam", "SLAM accuracy, time and memory over particle counts and seed 003 variants");
  command->add_option("--log", args->log, "CARMEN log")->required();
  command->add_option("--relations", args->relations, "Kümmerle relations file");
  command->add_option("--perturb-odometry", args->perturb_seed,
                      "Corrected log: replace its odometry by seeded synthetic odometry and "
                      "score by ATE against the corrected poses");
  command->add_option("--out", args->out, "Output folder (results.json, results.md, runs/)")
      ->required();
  command->add_option("--particles", args->particles, "Particle counts")->delimiter(',');
  command->add_option("--variants", args->variants, "plain, annealing, genetic, both")
      ->delimiter(',')
      ->check(CLI::IsMember({"plain", "annealing", "genetic", "both"}));
  command->add_option("--config", args->config, "SLAM options YAML passed to every run");
  command->add_option("--seed", args->seed, "Random seed of every run");
  command->add_option("--threads", args->threads, "Worker threads per run");
  command->add_option("--max-scans", args->max_scans, "Use only the first N scans");
  command->add_option("--every-scan", args->every_scan, "localize or interpolate");
  command->callback([args, &exit_code] { exit_code = RunBenchSlam(*args); });
}

}  // namespace

void AddBenchCommand(CLI::App& app, int& exit_code) {
  CLI::App* bench = app.add_subcommand(
      "bench", "Benchmarks: slam, localize (real logs), reloc (simulated relocalization trials)");
  bench->require_subcommand(1);
  AddBenchSlam(*bench, exit_code);
  AddBenchLocalize(*bench, exit_code);
  AddBenchReloc(*bench, exit_code);
  AddBenchDetector(*bench, exit_code);
}

}  // namespace semchain::app
