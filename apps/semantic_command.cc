// semchain semantic --run RUN --map MAP [--poses MAP/trajectory.txt] --out MAP
//                   [--detector M.onnx [--classes F] [--detector-input WxH]]
// Semantic mapping (DESIGN.md §3.4–3.5): the run's detections (RUN/detections.jsonl, or a
// YOLOv8-format model run on the frames) and depth frames, posed by the SLAM trajectory, onto
// the SLAM map; writes OUT/semantic.json, OUT/keyframes.json and OUT/semantic.png (and copies
// the map into OUT when OUT is another directory).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "apps/command.h"
#include "apps/semantic_outputs.h"
#include "core/atomic_file.h"
#include "core/progress_bar.h"
#include "io/trajectory_io.h"
#include "mapping/map_io.h"
#include "semantic/keyframe_selection.h"
#include "semantic/semantic_run.h"

namespace semchain::app {
namespace {

namespace fs = std::filesystem;

struct SemanticArgs {
  std::string run;
  std::string map;
  std::string poses;
  std::string out;
  double scale = 50.0;
  DetectorArgs detector;  // a YOLOv8-format ONNX model instead of RUN/detections.jsonl
  double min_detection_score = semantic::DetectionPointOptions().min_score;
};

Status RunSemantic(const SemanticArgs& args) {
  const fs::path map_dir(args.map);
  const fs::path out(args.out);
  Result<mapping::MapImage> map = mapping::ReadMap(map_dir / "map.yaml");
  if (!map.ok()) return map.status();
  if (map->origin.z() != 0.0) {
    return Status::Error((map_dir / "map.yaml").string() +
                         ": rotated map origins are not supported");
  }
  const fs::path poses_path =
      args.poses.empty() ? map_dir / "trajectory.txt" : fs::path(args.poses);
  Result<std::vector<StampedPose>> poses = ReadTrajectory(poses_path);
  if (!poses.ok()) return poses.status();

  semantic::SemanticRunInputs inputs;
  inputs.run_dir = args.run;
  if (!args.detector.model.empty()) {
    Result<std::vector<FrameDetections>> detections = DetectWithModel(args.detector, args.run);
    if (!detections.ok()) return detections.status();
    inputs.detections = std::move(*detections);
  }
  inputs.occupancy = *map;
  inputs.trajectory = std::move(*poses);
  inputs.trajectory_source = poses_path.string();
  std::optional<ProgressBar> progress;
  semantic::SemanticMapOptions options;
  options.points.min_score = args.min_detection_score;
  Result<semantic::SemanticMappingResult> result =
      semantic::MapRun(inputs, options, [&](std::size_t done, std::size_t total) {
        if (!progress) progress.emplace("semantic mapping", total);
        progress->Update(done);
      });
  if (progress) progress->Finish();
  if (!result.ok()) return result.status();

  // Everything is computed before anything is written; each file is written atomically.
  SEMCHAIN_RETURN_IF_ERROR(EnsureWritableDirectory(out));
  std::error_code error;
  if (fs::weakly_canonical(out, error) != fs::weakly_canonical(map_dir, error)) {
    SEMCHAIN_RETURN_IF_ERROR(mapping::WriteMap(out / "map.yaml", *map));
  }
  const semantic::KeyframeDatabase keyframes{fs::absolute(args.run).lexically_normal().string(),
                                             semantic::SelectCoveringKeyframes(result->keyframes)};
  SEMCHAIN_RETURN_IF_ERROR(WriteSemanticOutputs(out, *map, *result, keyframes, args.scale));
  std::printf("%s\nwrote %s\n", SemanticSummary(*result, keyframes.keyframes.size()).c_str(),
              (out / "semantic.json").string().c_str());
  return Status::Ok();
}

}  // namespace

void AddSemanticCommand(CLI::App& app, int& exit_code) {
  CLI::App* command = app.add_subcommand(
      "semantic",
      "Put the objects a run's RGB-D camera detected onto its SLAM map and link them into "
      "semantic chains: writes semantic.json, keyframes.json and semantic.png");
  auto args = std::make_shared<SemanticArgs>();
  command->add_option("--run", args->run, "Run directory (camera.yaml, detections.jsonl, frames/)")
      ->required();
  command->add_option("--map", args->map, "Map directory from `semchain slam` (map.yaml)")
      ->required();
  command->add_option("--poses", args->poses,
                      "Trajectory posing the frames (default: MAP/trajectory.txt)");
  command->add_option("--out", args->out, "Output directory (usually the map directory)")
      ->required();
  AddDetectorOptions(command, &args->detector, "reading RUN/detections.jsonl");
  command->add_option("--min-detection-score", args->min_detection_score, kMinDetectionScoreHelp)
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  command->add_option("--scale", args->scale, "Pixels per metre of semantic.png")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 1000.0));
  command->callback([args, &exit_code] {
    const Status status = RunSemantic(*args);
    exit_code = status.ok() ? 0 : ReportError(status);
  });
}

}  // namespace semchain::app
