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
#include <string>

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

Status RunLocalize(const LocalizeArgs& args) {
  const std::optional<localization::LocalizationMethod> method =
      localization::ParseLocalizationMethod(args.method);
  if (!method) {
    return Status::Error("--method: unknown method '" + args.method + "' (" +
                         localization::LocalizationMethodList() + ")");
  }
  const fs::path map_dir(args.map);
  const fs::path run(args.run);
  Result<semantic::MapFolder> folder = semantic::ReadMapFolder(map_dir);
  if (!folder.ok()) return folder.status();
  const mapping::MapImage* map = &folder->occupancy;
  const semantic::SemanticMap* semantic = &folder->semantic;

  Result<carmen::Log> log = carmen::ReadLog(run / "log.clf");
  if (!log.ok()) return log.status();
  Result<std::vector<StampedScan>> scans = mapping::ScansFromLog(*log, (run / "log.clf").string());
  if (!scans.ok()) return scans.status();
  std::vector<localization::LocalizerFrame> localizer_frames;
  if (localization::IsSemanticMethod(*method)) {
    Result<CameraInfo> camera = ReadCameraYaml(run / "camera.yaml");
    if (!camera.ok()) return camera.status();
    const std::string source = args.detector.model.empty()
                                   ? (run / "detections.jsonl").string()
                                   : args.detector.model + " on " + (run / "frames").string();
    Result<std::vector<FrameDetections>> frames =
        args.detector.model.empty() ? ReadDetectionsJsonl(run / "detections.jsonl")
                                    : DetectWithModel(args.detector, run);
    if (!frames.ok()) return frames.status();
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
  }
  localization::LocalizerMap reloc_map(*map, *semantic, localization::AmclOptions(),
                                       localization::PreLocalizationOptions(),
                                       localization::ScanMatchRelocalizerOptions());
  if (*method == localization::LocalizationMethod::kSemanticAmclBow) {
    if (args.vocab.empty()) {
      return Status::Error("--method semantic-amcl-bow needs --vocab (semchain vocab train)");
    }
    Result<bow::KeyframeRecognizer> recognizer =
        bow::LoadKeyframeRecognizer(args.vocab, folder->keyframes);
    if (!recognizer.ok()) return recognizer.status();
    reloc_map.recognizer = std::make_shared<const bow::KeyframeRecognizer>(std::move(*recognizer));
  }
  localization::LocalizerOptions options;
  options.seed = static_cast<std::uint64_t>(args.seed);
  localization::Localizer localizer(reloc_map, *method, options);
  // The localizer keeps the frames until the scan they belong to; it reads an image only when
  // the bag of words asks for one.
  for (localization::LocalizerFrame& frame : localizer_frames) localizer.AddFrame(std::move(frame));
  // Every update is kept: the picture chooses which to draw once it knows how many there were.
  localization::RelocTraceRecorder recorder(args.png.empty() ? 0 : 1);
  for (const StampedScan& scan : *scans) recorder.AddScan(scan, localizer);
  const localization::RelocTrace trace = recorder.Finish(localizer);

  nlohmann::json result = {{"method", args.method},
                           {"scans", scans->size()},
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
  std::vector<StampedPose> truth;
  if (fs::exists(run / "truth.txt")) {
    Result<std::vector<StampedPose>> read = ReadTrajectory(run / "truth.txt");
    if (!read.ok()) return read.status();
    truth = std::move(*read);
    if (last && !truth.empty()) {
      const Pose2& t = truth.back().pose;
      result["error_m"] = (last->translation() - t.translation()).norm();
      result["error_deg"] = std::abs(NormalizeAngle(last->theta - t.theta)) * 180.0 / M_PI;
    }
  }
  if (!args.png.empty()) {
    RelocPictureOptions picture;
    picture.method = args.method;
    for (const StampedScan& scan : *scans) picture.scan_times.push_back(scan.scan.timestamp);
    for (const StampedPose& pose : truth) picture.truth.push_back(pose.pose);
    SEMCHAIN_RETURN_IF_ERROR(
        WriteRelocalizationPng(*map, *semantic, trace, picture, fs::path(args.png)));
  }
  const std::string text = result.dump(2) + "\n";
  if (!args.out.empty()) SEMCHAIN_RETURN_IF_ERROR(WriteFileAtomically(args.out, text));
  std::printf("%s", text.c_str());
  return Status::Ok();
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
