// semchain localize --map MAP --run RUN --method METHOD [--out R.json] [--png P.png] [--seed S]
//                   [--detector M.onnx]
// Runs one relocalization method (DESIGN.md §4) over a recorded run (its scans, odometry and
// camera detections) on a map with its semantic map; prints (and writes) the result as JSON,
// scored against RUN/truth.txt when the run has one, and draws it (particles converging).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "apps/command.h"
#include "apps/reloc_drawing.h"
#include "apps/semantic_outputs.h"
#include "bow/bow_occlusion.h"
#include "core/angles.h"
#include "core/atomic_file.h"
#include "io/camera_io.h"
#include "io/carmen.h"
#include "io/detections_io.h"
#include "io/rgbd_frame_io.h"
#include "io/trajectory_io.h"
#include "localization/localizer.h"
#include "localization/reloc_trace.h"
#include "mapping/map_io.h"
#include "mapping/slam_pipeline.h"
#include "semantic/map_folder.h"

namespace semchain::app {
namespace {

namespace fs = std::filesystem;

struct LocalizeArgs {
  std::string map;
  std::string run;
  std::string method;
  std::string out;
  std::string png;
  std::string vocab;      // semantic-amcl-bow
  DetectorArgs detector;  // a YOLOv8-format ONNX model instead of RUN/detections.jsonl
  int seed = 1;
};

// What the localizer is fed from RUN: its scans and, for the semantic methods, its camera frames.
struct RunInputs {
  std::vector<StampedScan> scans;
  std::vector<localization::LocalizerFrame> frames;
};

Result<std::vector<localization::LocalizerFrame>> ReadFrames(const LocalizeArgs& args,
                                                             const fs::path& run) {
  Result<CameraInfo> camera = ReadCameraYaml(run / "camera.yaml");
  if (!camera.ok()) return camera.status();
  const std::string source = args.detector.model.empty()
                                 ? (run / "detections.jsonl").string()
                                 : args.detector.model + " on " + (run / "frames").string();
  Result<std::vector<FrameDetections>> frames = args.detector.model.empty()
                                                    ? ReadDetectionsJsonl(run / "detections.jsonl")
                                                    : DetectWithModel(args.detector, run);
  if (!frames.ok()) return frames.status();
  std::vector<localization::LocalizerFrame> localizer_frames;
  std::size_t detections = 0;
  for (const FrameDetections& frame : *frames) {
    detections += frame.detections.size();
    localizer_frames.push_back({frame.stamp, frame.detections, camera->camera, cv::Mat(),
                                ColorImagePath(run, frame.frame)});
  }
  if (detections == 0) {
    return Status::Error(source + ": no detections at all: " + args.method +
                         " needs objects in view (use amcl or scanmatch-global)");
  }
  return localizer_frames;
}

Result<RunInputs> ReadRunInputs(const LocalizeArgs& args, localization::LocalizationMethod method) {
  const fs::path run(args.run);
  Result<carmen::Log> log = carmen::ReadLog(run / "log.clf");
  if (!log.ok()) return log.status();
  Result<std::vector<StampedScan>> scans = mapping::ScansFromLog(*log, (run / "log.clf").string());
  if (!scans.ok()) return scans.status();
  RunInputs inputs;
  inputs.scans = std::move(*scans);
  if (localization::IsSemanticMethod(method)) {
    Result<std::vector<localization::LocalizerFrame>> frames = ReadFrames(args, run);
    if (!frames.ok()) return frames.status();
    inputs.frames = std::move(*frames);
  }
  return inputs;
}

// semantic-amcl-bow recognizes the map's keyframes with the bag of words of --vocab.
Status AddRecognizer(const LocalizeArgs& args, localization::LocalizationMethod method,
                     const semantic::MapFolder& folder, localization::LocalizerMap* reloc_map) {
  if (method != localization::LocalizationMethod::kSemanticAmclBow) return Status::Ok();
  if (args.vocab.empty()) {
    return Status::Error("--method semantic-amcl-bow needs --vocab (semchain vocab train)");
  }
  Result<bow::KeyframeRecognizer> recognizer =
      bow::LoadKeyframeRecognizer(args.vocab, folder.keyframes);
  if (!recognizer.ok()) return recognizer.status();
  reloc_map->recognizer = std::make_shared<const bow::KeyframeRecognizer>(std::move(*recognizer));
  return Status::Ok();
}

localization::RelocTrace RunLocalizer(const LocalizeArgs& args,
                                      const localization::LocalizerMap& reloc_map,
                                      localization::LocalizationMethod method, RunInputs& inputs) {
  localization::LocalizerOptions options;
  options.seed = static_cast<std::uint64_t>(args.seed);
  localization::Localizer localizer(reloc_map, method, options);
  // The localizer keeps the frames until the scan they belong to; it reads an image only when
  // the bag of words asks for one.
  for (localization::LocalizerFrame& frame : inputs.frames) localizer.AddFrame(std::move(frame));
  // Every update is kept: the picture chooses which to draw once it knows how many there were.
  localization::RelocTraceRecorder recorder(args.png.empty() ? 0 : 1);
  for (const StampedScan& scan : inputs.scans) recorder.AddScan(scan, localizer);
  return recorder.Finish(localizer);
}

nlohmann::json ResultJson(const std::string& method, std::size_t scans,
                          const localization::RelocTrace& trace) {
  nlohmann::json result = {{"method", method},
                           {"scans", scans},
                           {"cpu_ms", 1000.0 * trace.cpu_seconds.back()},
                           {"iterations", trace.iterations.back()},
                           {"prelocalizations", trace.prelocalizations},
                           {"undecided_prelocalizations", trace.undecided_prelocalizations},
                           {"lock_corrections", trace.lock_corrections},
                           {"lock_rechecks", trace.lock_rechecks}};
  const auto& last = trace.estimates.back();
  result["localized"] = last.has_value();
  if (last) result["pose"] = {last->x, last->y, last->theta};
  if (trace.prelocalization) {
    result["prelocalization"] = {trace.prelocalization->x, trace.prelocalization->y,
                                 trace.prelocalization->theta};
  }
  return result;
}

// RUN/truth.txt when the run has one (empty otherwise); the final estimate's error against its
// last pose goes into the result.
Result<std::vector<StampedPose>> ScoreAgainstTruth(const fs::path& run,
                                                   const std::optional<Pose2>& last,
                                                   nlohmann::json* result) {
  std::vector<StampedPose> truth;
  if (!fs::exists(run / "truth.txt")) return truth;
  Result<std::vector<StampedPose>> read = ReadTrajectory(run / "truth.txt");
  if (!read.ok()) return read.status();
  truth = std::move(*read);
  if (last && !truth.empty()) {
    const Pose2& t = truth.back().pose;
    (*result)["error_m"] = (last->translation() - t.translation()).norm();
    (*result)["error_deg"] = std::abs(NormalizeAngle(last->theta - t.theta)) * 180.0 / M_PI;
  }
  return truth;
}

// The picture (--png), the JSON file (--out), then the JSON on stdout.
Status WriteResult(const LocalizeArgs& args, const semantic::MapFolder& folder,
                   const localization::RelocTrace& trace, const std::vector<StampedScan>& scans,
                   const std::vector<StampedPose>& truth, const nlohmann::json& result) {
  if (!args.png.empty()) {
    RelocPictureOptions picture;
    picture.method = args.method;
    for (const StampedScan& scan : scans) picture.scan_times.push_back(scan.scan.timestamp);
    for (const StampedPose& pose : truth) picture.truth.push_back(pose.pose);
    SEMCHAIN_RETURN_IF_ERROR(WriteRelocalizationPng(folder.occupancy, folder.semantic, trace,
                                                    picture, fs::path(args.png)));
  }
  const std::string text = result.dump(2) + "\n";
  if (!args.out.empty()) SEMCHAIN_RETURN_IF_ERROR(WriteFileAtomically(args.out, text));
  std::printf("%s", text.c_str());
  return Status::Ok();
}

Status RunLocalize(const LocalizeArgs& args) {
  const std::optional<localization::LocalizationMethod> method =
      localization::ParseLocalizationMethod(args.method);
  if (!method) {
    return Status::Error("--method: unknown method '" + args.method + "' (" +
                         localization::LocalizationMethodList() + ")");
  }
  Result<semantic::MapFolder> folder = semantic::ReadMapFolder(fs::path(args.map));
  if (!folder.ok()) return folder.status();
  Result<RunInputs> inputs = ReadRunInputs(args, *method);
  if (!inputs.ok()) return inputs.status();
  localization::LocalizerMap reloc_map(
      folder->occupancy, folder->semantic, localization::AmclOptions(),
      localization::PreLocalizationOptions(), localization::ScanMatchRelocalizerOptions());
  SEMCHAIN_RETURN_IF_ERROR(AddRecognizer(args, *method, *folder, &reloc_map));
  const localization::RelocTrace trace = RunLocalizer(args, reloc_map, *method, *inputs);
  nlohmann::json result = ResultJson(args.method, inputs->scans.size(), trace);
  const Result<std::vector<StampedPose>> truth =
      ScoreAgainstTruth(fs::path(args.run), trace.estimates.back(), &result);
  if (!truth.ok()) return truth.status();
  return WriteResult(args, *folder, trace, inputs->scans, *truth, result);
}

}  // namespace

void AddLocalizeCommand(CLI::App& app, int& exit_code) {
  CLI::App* command = app.add_subcommand(
      "localize",
      "Relocalize a recorded run on a map: amcl, semantic-amcl, semantic-amcl-bow, "
      "semantic-scanmatch or "
      "scanmatch-global; prints the pose (and its error against RUN/truth.txt) as JSON");
  auto args = std::make_shared<LocalizeArgs>();
  command->add_option("--map", args->map, "Map directory (map.yaml, semantic.json)")->required();
  command->add_option("--run", args->run, "Run directory (log.clf, detections.jsonl, camera.yaml)")
      ->required();
  command->add_option("--method", args->method, "Relocalization method")->required();
  command->add_option("--out", args->out, "Also write the JSON here");
  command->add_option("--png", args->png,
                      "Draw the relocalization here: map, objects, particle clouds over time "
                      "(light = early), truth and final estimate");
  command->add_option("--vocab", args->vocab,
                      "Vocabulary (semchain vocab train) for semantic-amcl-bow; the keyframes are "
                      "MAP/keyframes.json");
  AddDetectorOptions(command, &args->detector, "reading RUN/detections.jsonl");
  command->add_option("--seed", args->seed, "Seed of the filters")->capture_default_str();
  command->callback([args, &exit_code] {
    const Status status = RunLocalize(*args);
    exit_code = status.ok() ? 0 : ReportError(status);
  });
}

}  // namespace semchain::app
