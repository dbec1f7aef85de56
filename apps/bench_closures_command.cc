// semchain bench closures --log L.clf (--relations R | --reference POSES | --perturb-odometry N)
//     [--config C.yaml] [--particles N] [--seed S] [--oracle | --oracle-poses] --out DIR
// Runs SLAM with the pose graph on, records every match its loop-closure searches score
// (LoopClosureOptions::record_candidates) and labels each by the reference: true when its
// relative pose is within 0.3 m and 2° of the reference's between the two nodes' scans
// (eval/closure_reference.h). Writes DIR/closures.csv (a row a candidate), DIR/results.json and
// DIR/results.md (precision and recall at each score threshold: the score alone, after
// verification, after the back end), DIR/precision_recall.png and DIR/trajectory.txt, with the
// run's aligned ATE (reference poses) or relation errors (relations). With --oracle the
// reference verifies the closures (LoopClosureOptions::oracle): what a perfect verifier gives;
// with --oracle-poses every closure that passed the score goes in at the reference's relative
// pose (LoopClosureOptions::oracle_relative): what a perfect matcher and verifier give.
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>

#include "apps/closures_drawing.h"
#include "apps/closures_report.h"
#include "apps/command.h"
#include "core/angles.h"
#include "core/atomic_file.h"
#include "core/progress_bar.h"
#include "eval/ate.h"
#include "eval/closure_metrics.h"
#include "eval/relations.h"
#include "io/carmen.h"
#include "io/trajectory_io.h"
#include "mapping/odometry_perturbation.h"
#include "mapping/slam_options_io.h"
#include "mapping/slam_pipeline.h"

namespace semchain::app {
// Helpers in a namespace of their own: unity builds compile several files as one.
namespace {
namespace bench_closures {

struct BenchClosuresArgs {
  std::string log, relations, reference, config, out;
  std::optional<int> perturb_seed, particles, seed, threads, max_scans;
  double record_min_score = 0.4;
  double min_weight = 0.5;
  bool oracle = false;
  bool oracle_poses = false;
  eval::ClosureLabelOptions label;
  eval::ClosureReferenceOptions reference_options;
};

// The log SLAM runs on and what it is judged against.
struct Prepared {
  std::vector<StampedScan> scans;
  std::vector<StampedPose> truth;  // reference poses (by index when perturbed)
  std::vector<eval::Relation> relations;
  std::unique_ptr<eval::ClosureReference> reference;
  std::string kind;  // for the report
};

Result<mapping::SlamOptions> BuildOptions(const BenchClosuresArgs& args) {
  mapping::SlamOptions options;
  if (!args.config.empty()) {
    SEMCHAIN_RETURN_IF_ERROR(mapping::LoadSlamOptions(args.config, &options));
  }
  if (args.particles) options.rbpf.particles = *args.particles;
  if (args.seed) options.rbpf.seed = static_cast<std::uint64_t>(*args.seed);
  if (args.threads) options.rbpf.threads = *args.threads;
  options.pose_graph = true;
  options.loop_closure.record_candidates = true;
  options.loop_closure.record_min_score = args.record_min_score;
  std::string error;
  if (!options.Validate(&error)) return Status::Error("invalid SLAM options: " + error);
  return options;
}

eval::ScanTrack TrackOf(const std::vector<StampedScan>& scans) {
  eval::ScanTrack track;
  for (const StampedScan& scan : scans) {
    track.timestamps.push_back(scan.scan.timestamp);
    track.odometry.push_back(scan.odometry);
  }
  return track;
}

Result<Prepared> Prepare(const BenchClosuresArgs& args) {
  Result<carmen::Log> log = carmen::ReadLog(args.log);
  if (!log.ok()) return log.status();
  Prepared prepared;
  if (args.perturb_seed) {
    mapping::OdometryPerturbationOptions perturbation;
    perturbation.seed = static_cast<std::uint64_t>(*args.perturb_seed);
    mapping::PerturbedLog perturbed = mapping::PerturbOdometry(*log, perturbation);
    *log = std::move(perturbed.log);
    prepared.truth = std::move(perturbed.truth);
  }
  mapping::ReversedOdometryRepair repair;
  Result<std::vector<StampedScan>> scans = mapping::ScansFromLog(*log, args.log, &repair);
  if (!scans.ok()) return scans.status();
  if (args.max_scans && static_cast<std::size_t>(*args.max_scans) < scans->size()) {
    scans->resize(static_cast<std::size_t>(*args.max_scans));
  }
  prepared.scans = std::move(*scans);
  if (args.perturb_seed) {
    std::vector<Pose2> poses;
    for (const StampedPose& pose : prepared.truth) poses.push_back(pose.pose);
    prepared.reference = eval::MakeIndexedReference(std::move(poses));
    prepared.kind = "the log's corrected poses (odometry perturbed, seed " +
                    std::to_string(*args.perturb_seed) + "), paired by scan";
  } else if (!args.reference.empty()) {
    Result<std::vector<StampedPose>> truth = ReadTrajectory(args.reference);
    if (!truth.ok()) return truth.status();
    prepared.truth = std::move(*truth);
    prepared.reference =
        eval::MakeTimedReference(prepared.truth, TrackOf(prepared.scans), args.reference_options);
    prepared.kind = "reference poses " + args.reference;
  } else {
    Result<std::vector<eval::Relation>> relations = eval::ReadRelations(args.relations);
    if (!relations.ok()) return relations.status();
    prepared.relations = std::move(*relations);
    prepared.reference = eval::MakeRelationReference(prepared.relations, TrackOf(prepared.scans),
                                                     args.reference_options);
    prepared.kind = "relations " + args.relations;
  }
  return prepared;
}

// The run's accuracy against the reference: ATE (unaligned and aligned) or relation errors.
Result<nlohmann::json> Accuracy(const std::vector<StampedPose>& trajectory,
                                const Prepared& prepared, bool by_index, std::string* text) {
  if (!prepared.relations.empty()) {
    const Result<eval::RelationErrors> errors =
        eval::EvaluateRelations(trajectory, prepared.relations);
    if (!errors.ok()) return errors.status();
    char buffer[128];
    std::snprintf(buffer, sizeof(buffer), "relation error %.4f ± %.4f m, %.3f° (%zu relations)",
                  errors->trans_mean_m, errors->trans_std_m, errors->rot_mean_deg, errors->matched);
    *text = buffer;
    return nlohmann::json::parse(eval::RelationErrorsToJson(*errors));
  }
  std::vector<StampedPose> truth = prepared.truth;
  eval::AteOptions options;
  options.pair_by_index = by_index;
  if (by_index) truth.resize(std::min(truth.size(), trajectory.size()));
  const Result<eval::AteResult> plain = eval::EvaluateAte(trajectory, truth, options);
  if (!plain.ok()) return plain.status();
  options.align = true;
  const Result<eval::AteResult> aligned = eval::EvaluateAte(trajectory, truth, options);
  if (!aligned.ok()) return aligned.status();
  nlohmann::json json = nlohmann::json::parse(eval::AteResultToJson(*plain));
  json["ate_rmse_aligned_m"] = aligned->ate_rmse_m;
  json["ate_max_aligned_m"] = aligned->ate_max_m;
  char buffer[160];
  std::snprintf(buffer, sizeof(buffer),
                "ATE RMSE %.3f m, max %.3f m; aligned RMSE %.3f m, max %.3f m (%zu poses)",
                plain->ate_rmse_m, plain->ate_max_m, aligned->ate_rmse_m, aligned->ate_max_m,
                aligned->matched);
  *text = buffer;
  return json;
}

std::vector<double> Thresholds(double lowest) {
  std::vector<double> thresholds;
  for (int k = static_cast<int>(std::lround(lowest * 20.0)); k <= 19; ++k) {
    thresholds.push_back(0.05 * k);
  }
  return thresholds;
}

nlohmann::json FalseInGraph(const std::vector<eval::LabelledCandidate>& candidates) {
  nlohmann::json list = nlohmann::json::array();
  for (const eval::LabelledCandidate& l : candidates) {
    const mapping::LoopClosureCandidate& c = l.candidate;
    if (l.label != eval::ClosureLabel::kFalse ||
        (c.verification != mapping::ClosureVerification::kAdded &&
         c.verification != mapping::ClosureVerification::kConfirmed)) {
      continue;
    }
    list.push_back({{"from_node", c.from},
                    {"to_node", c.to},
                    {"from_scan", c.from_scan},
                    {"to_scan", c.to_scan},
                    {"score", c.score},
                    {"verification", eval::ToString(c.verification)},
                    {"translation_error_m", l.translation_error_m},
                    {"rotation_error_deg", RadToDeg(l.rotation_error_rad)},
                    {"in_graph", c.in_graph},
                    {"weight", c.weight}});
  }
  return list;
}

const char* LossName(mapping::RobustLoss loss) {
  switch (loss) {
    case mapping::RobustLoss::kNone:
      return "none";
    case mapping::RobustLoss::kHuber:
      return "huber";
    case mapping::RobustLoss::kCauchy:
      return "cauchy";
    case mapping::RobustLoss::kDynamicCovarianceScaling:
      return "dcs";
  }
  return "?";
}

nlohmann::json PoseGraphJson(const mapping::LoopClosureStatistics& l) {
  return {{"nodes", l.nodes},
          {"submaps", l.submaps},
          {"searches", l.searches},
          {"closures_found", l.found},
          {"closures_accepted", l.accepted},
          {"closures_rejected", l.rejected},
          {"closures_gated", l.gated},
          {"motion_edges_loosened", l.loosened},
          {"search_seconds", l.search_seconds},
          {"optimizer_seconds", l.optimizer_seconds}};
}

Status WriteResults(const BenchClosuresArgs& args, const mapping::SlamOptions& options,
                    const Prepared& prepared, const mapping::SlamResult& result, double seconds) {
  const std::filesystem::path out(args.out);
  std::vector<eval::LabelledCandidate> labelled;
  for (const mapping::LoopClosureCandidate& c : result.loop_closure_candidates) {
    labelled.push_back(eval::LabelCandidate(c, *prepared.reference, args.label));
  }
  const eval::ClosureTable table =
      eval::PrecisionRecall(labelled, Thresholds(args.record_min_score), args.min_weight);
  nlohmann::json results = {
      {"log", args.log},
      {"reference", prepared.kind},
      {"config", args.config.empty() ? std::string("default") : args.config},
      {"particles", options.rbpf.particles},
      {"seed", options.rbpf.seed},
      {"scans", prepared.scans.size()},
      {"slam_seconds", seconds},
      {"record_min_score", args.record_min_score},
      {"min_score", options.loop_closure.min_score},
      {"min_weight", args.min_weight},
      {"oracle_verification", args.oracle},
      {"oracle_poses", args.oracle_poses},
      {"loop_loss", LossName(options.loop_closure.optimizer.loop_loss)},
      {"label_max_translation_m", args.label.max_translation_meters},
      {"label_max_rotation_deg", RadToDeg(args.label.max_rotation_radians)},
      {"pose_graph", PoseGraphJson(result.loop_closure)},
      {"table", ClosureTableJson(table)},
      {"histogram", ScoreHistogramJson(labelled, args.record_min_score, 0.05)},
      {"false_in_graph", FalseInGraph(labelled)}};
  std::string accuracy_text;
  const Result<nlohmann::json> accuracy =
      Accuracy(result.trajectory, prepared, args.perturb_seed.has_value(), &accuracy_text);
  if (accuracy.ok()) {
    results["accuracy"] = *accuracy;
    results["accuracy_text"] = accuracy_text;
  } else {
    spdlog::warn("bench closures: no accuracy: {}", accuracy.status().message());
  }
  std::vector<double> times;
  for (const StampedScan& scan : prepared.scans) times.push_back(scan.scan.timestamp);
  SEMCHAIN_RETURN_IF_ERROR(WriteTrajectory(out / "trajectory.txt", result.trajectory));
  SEMCHAIN_RETURN_IF_ERROR(WriteFileAtomically(out / "closures.csv", ClosuresCsv(labelled, times)));
  SEMCHAIN_RETURN_IF_ERROR(WriteFileAtomically(out / "results.json", results.dump(2) + "\n"));
  SEMCHAIN_RETURN_IF_ERROR(WriteFileAtomically(out / "results.md", ClosuresMarkdown(results)));
  const std::string title = std::filesystem::path(args.log).filename().string() +
                            ": loop-closure candidates, precision vs recall";
  return WritePrecisionRecallPng(table, title, out / "precision_recall.png");
}

int RunBenchClosures(const BenchClosuresArgs& args) {
  const int references = (args.relations.empty() ? 0 : 1) + (args.reference.empty() ? 0 : 1) +
                         (args.perturb_seed ? 1 : 0);
  if (references != 1) {
    return ReportError(Status::Error(
        "bench closures: give exactly one of --relations, --reference, --perturb-odometry"));
  }
  Result<mapping::SlamOptions> options = BuildOptions(args);
  if (!options.ok()) return ReportError(options.status());
  const Status writable = EnsureWritableDirectory(args.out);
  if (!writable.ok()) return ReportError(writable);
  Result<Prepared> prepared = Prepare(args);
  if (!prepared.ok()) return ReportError(prepared.status());
  if (args.oracle_poses) {
    // Every closure that passed the score goes in at the reference's relative pose.
    const eval::ClosureReference* reference = prepared->reference.get();
    options->loop_closure.oracle_relative =
        [reference](const mapping::LoopClosureCandidate& c) -> std::optional<Pose2> {
      if (c.from_scan < 0 || c.to_scan < 0) return std::nullopt;
      return reference->Relative(c.from_scan, c.to_scan);
    };
  } else if (args.oracle) {
    // Only the closures the reference labels true go in: the map a perfect verifier would give.
    const eval::ClosureReference* reference = prepared->reference.get();
    options->loop_closure.oracle = [reference, &args](const mapping::LoopClosureCandidate& c) {
      return eval::LabelCandidate(c, *reference, args.label).label == eval::ClosureLabel::kTrue;
    };
  }
  spdlog::info("bench closures: {} scans, {} particles, candidates scored down to {:.2f}",
               prepared->scans.size(), options->rbpf.particles, args.record_min_score);
  ProgressBar bar("slam", 2 * prepared->scans.size());
  const auto start = std::chrono::steady_clock::now();
  const mapping::SlamResult result =
      mapping::RunSlam(prepared->scans, *options, [&bar](std::size_t done) { bar.Update(done); });
  bar.Finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const Status written = WriteResults(args, *options, *prepared, result, seconds);
  if (!written.ok()) return ReportError(written);
  spdlog::info("bench closures: {} candidates; wrote {}", result.loop_closure_candidates.size(),
               (std::filesystem::path(args.out) / "results.md").string());
  return 0;
}

}  // namespace bench_closures
}  // namespace

void AddBenchClosures(CLI::App& bench, int& exit_code) {
  auto args = std::make_shared<bench_closures::BenchClosuresArgs>();
  CLI::App* command = bench.add_subcommand(
      "closures",
      "The loop closer as a detector: every candidate it scores labelled by a reference, "
      "precision and recall at each score threshold before and after verification and the "
      "back end");
  command->add_option("--log", args->log, "CARMEN log (.clf, .log, .gz)")->required();
  command->add_option("--relations", args->relations, "Kümmerle relations of the log");
  command->add_option("--reference", args->reference,
                      "Reference poses 'timestamp x y theta' on the log's clock (RUN/truth.txt)");
  command->add_option("--perturb-odometry", args->perturb_seed,
                      "Corrected log: replace its odometry by seeded synthetic odometry; its "
                      "own poses are the reference");
  command->add_option("--config", args->config, "SLAM options YAML (the pose graph is turned on)");
  command->add_option("--particles", args->particles, "Number of particles")
      ->check(CLI::Range(1, 10000));
  command->add_option("--seed", args->seed, "Random seed")->check(CLI::NonNegativeNumber);
  command->add_option("--threads", args->threads, "Worker threads")->check(CLI::Range(1, 256));
  command->add_option("--max-scans", args->max_scans, "Use only the first N scans")
      ->check(CLI::PositiveNumber);
  command
      ->add_option("--score-floor", args->record_min_score,
                   "Candidates are recorded down to this score (the tables start there)")
      ->check(CLI::Range(0.05, 1.0))
      ->capture_default_str();
  command
      ->add_option("--max-bridge", args->reference_options.max_bridge_meters,
                   "Odometry travel (m) a scan without a reference of its own may be bridged")
      ->capture_default_str();
  command
      ->add_option("--max-bridge-turn", args->reference_options.max_bridge_radians,
                   "...and turning (rad)")
      ->capture_default_str();
  CLI::Option* oracle =
      command->add_flag("--oracle", args->oracle,
                        "Verify by the reference: a closure that passed the score goes into the "
                        "graph only when it is true (the map a perfect verifier would give)");
  command
      ->add_flag("--oracle-poses", args->oracle_poses,
                 "Measurement: every closure that passed the score goes into the graph at the "
                 "reference's relative pose (dropped where the reference cannot join its "
                 "scans): what exactly right closures give")
      ->excludes(oracle);
  command->add_option("--out", args->out, "Output folder")->required();
  command->callback([args, &exit_code] { exit_code = bench_closures::RunBenchClosures(*args); });
}

}  // namespace semchain::app
