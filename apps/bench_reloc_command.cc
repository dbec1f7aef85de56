// semchain bench reloc --world W.yaml [--live-world W2.yaml] --trials N --seed S
//                      --methods M1,M2,... [--detector M.onnx] [--runs RUNS] --out DIR
// The papers' relocalization experiment (DESIGN.md §4): map from a simulated mapping run of
// --world (SLAM + semantic mapping), trials at random poses in the trial region of --live-world;
// writes DIR/results.json and DIR/results.md.
#include <spdlog/spdlog.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/command.h"
#include "apps/semantic_outputs.h"
#include "apps/shipped_file.h"
#include "core/atomic_file.h"
#include "core/progress_bar.h"
#include "eval/reloc_benchmark.h"

namespace semchain::app {
namespace {

struct BenchRelocArgs {
  std::string world;
  std::string live_world;
  std::string out;
  eval::RelocBenchmarkOptions options;
  DetectorArgs detector;  // a YOLOv8-format ONNX model instead of the simulator's detections
  int seed = 1;
  std::string runs;  // keep and reuse the runs here (empty: a temporary folder)
};

int RunBenchReloc(BenchRelocArgs args) {
  const std::filesystem::path out(args.out);
  const Status writable = EnsureWritableDirectory(out);
  if (!writable.ok()) return ReportError(writable);
  args.options.seed = static_cast<std::uint64_t>(args.seed);
  if (!args.runs.empty()) {
    args.options.work_dir = args.runs;
    args.options.keep_runs = true;
  }
  if (!args.detector.model.empty()) {
    Result<RunDetectorFunction> detect = LoadRunDetector(args.detector, /*show_progress=*/false);
    if (!detect.ok()) return ReportError(detect.status());
    args.options.detect = std::move(*detect);
    args.options.detections_source = args.detector.model;
  }
  std::optional<ProgressBar> bar;
  const Result<eval::RelocBenchmarkResult> result =
      eval::RunRelocBenchmark(args.world, args.live_world.empty() ? args.world : args.live_world,
                              args.options, [&bar](int done, int total) {
                                if (!bar)
                                  bar.emplace("bench reloc", static_cast<std::size_t>(total));
                                bar->Update(static_cast<std::size_t>(done));
                              });
  if (bar) bar->Finish();
  if (!result.ok()) return ReportError(result.status());
  const Status json = WriteFileAtomically(out / "results.json", eval::RelocResultsJson(*result));
  if (!json.ok()) return ReportError(json);
  const std::string markdown = eval::RelocResultsMarkdown(*result);
  const Status md = WriteFileAtomically(out / "results.md", markdown);
  if (!md.ok()) return ReportError(md);
  std::printf("%s", markdown.c_str());
  return 0;
}

}  // namespace

void AddBenchReloc(CLI::App& bench, int& exit_code) {
  auto args = std::make_shared<BenchRelocArgs>();
  CLI::App* command = bench.add_subcommand(
      "reloc",
      "Relocalization trials in a simulated world (seed 000 Tables 4-5): map from a mapping run, "
      "random starts in the trial region, every method on the same recordings");
  command->add_option("--world", args->world, "World to map (YAML)")
      ->required()
      ->transform(ShippedFile());
  command
      ->add_option("--live-world", args->live_world,
                   "World the trials run in (default: --world; a changed world models seed "
                   "000 §4.2)")
      ->transform(ShippedFile());
  command->add_option("--trials", args->options.trials, "Number of trials")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command->add_option("--seed", args->seed, "Seed of the mapping run, trial starts and filters")
      ->capture_default_str();
  command
      ->add_option("--methods", args->options.methods,
                   "amcl, semantic-amcl, semantic-amcl-bow, semantic-scanmatch, scanmatch-global "
                   "(comma-separated)")
      ->delimiter(',');
  command->add_flag(
      "!--no-observation-memory", args->options.method.observation_memory,
      "Pre-localize from the current frame's objects only, not from all seen during the turn");
  command->add_flag("!--no-single-object", args->options.method.single_object,
                    "semantic-scanmatch: no single-object hypotheses before the whole-map search");
  command->add_flag("!--no-laser-refine", args->options.prelocalization.laser_refine,
                    "Pre-localization hypotheses from the objects alone, not refined by the laser "
                    "scan");
  command
      ->add_option("--pair-distance-slack", args->options.prelocalization.distance_slack,
                   "Metres an observed pair's distance may miss the mapped one by before the "
                   "relative tolerance α applies (0: seed 001's α alone)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--unknown-reach", args->options.prelocalization.unknown_reach,
                   "Metres from the map's free space within which a pre-localization hypothesis "
                   "may lie on cells the mapping run never saw (0: free space only)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--decision-min-laser-score", args->options.method.decision_min_laser_score,
                   "Laser fit (0-1) the place a pre-localization decides on must reach (0: any "
                   "the pre-localizer keeps)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  command->add_flag("!--no-lock-recheck", args->options.method.recheck_lock,
                    "semantic-scanmatch: do not re-check the lock against later frames' objects");
  command->add_flag("!--recheck-every-frame", args->options.method.recheck_on_new_evidence_only,
                    "semantic-scanmatch: re-check the lock at every frame, also when nothing new "
                    "was seen since a re-check that found nothing");
  command->add_flag(
      "--trial-face-open", args->options.trial_face_open,
      "Active relocalization: after the turns the robot drives towards the most "
      "open heading instead of straight on (not the protocol of docs/results.md's tables)");
  command
      ->add_option("--trial-turns-after", args->options.trial_turns_after,
                   "Turns in place where the drive ended (0: none; the protocol of "
                   "docs/results.md's tables)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  AddDetectorOptions(command, &args->detector,
                     "the simulator's detection model (the mapping run's and every trial's)");
  command->add_option("--out", args->out, "Output folder (results.json, results.md)")->required();
  command->add_option("--runs", args->runs,
                      "Keep the mapping run (map in DIR/mapping/map) and every trial's recording "
                      "(DIR/trial_K) here; a later call with the same worlds, seed and trial "
                      "settings reuses them instead of simulating again");
  command->callback([args, &exit_code] { exit_code = RunBenchReloc(*args); });
}

}  // namespace semchain::app
