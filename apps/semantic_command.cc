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
#include "apps/map_grey.h"
#include "apps/semantic_drawing.h"
#include "core/atomic_file.h"
#include "core/progress_bar.h"
#include "detection/run_detection.h"
#include "detection/yolo_detector.h"
#include "io/trajectory_io.h"
#include "mapping/map_io.h"
#include "semantic/keyframes.h"
#include "semantic/semantic_chain.h"
#include "semantic/semantic_map_io.h"
#include "semantic/semantic_run.h"
#include "sim/world_drawing.h"

namespace semchain::app {
namespace {

namespace fs = std::filesystem;

struct SemanticArgs {
  std::string run;
  std::string map;
  std::string poses;
  std::string out;
  double scale = 50.0;
  std::string detector;  // a YOLOv8-format ONNX model instead of RUN/detections.jsonl
  std::string classes;
  std::string detector_input = "320x256";
};

// The detections of the run's frames by the model of --detector.
Result<std::vector<FrameDetections>> DetectWithModel(const SemanticArgs& args) {
  detection::YoloOptions options;
  SEMCHAIN_RETURN_IF_ERROR(detection::ParseInputSize(args.detector_input, &options));
  std::string invalid;
  if (!options.Validate(&invalid)) return Status::Error("--detector-input: " + invalid);
  Result<std::unique_ptr<detection::YoloDetector>> detector =
      detection::LoadYoloDetector(args.detector, args.classes, options);
  if (!detector.ok()) return detector.status();
  detection::RunDetectionOptions run_options;
  run_options.show_progress = true;
  return detection::DetectRunFrames(**detector, args.run, run_options);
}

// The grey map with the free cells of odd regions a shade darker, so that the regions the
// chains are built on can be told apart.
cv::Mat MapWithRegions(const mapping::MapImage& map, const semantic::RegionMap& regions) {
  cv::Mat grey = MapToGrey(map);
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      if (map.At(x, y) == 0 && regions.labels.at<int>(y, x) % 2 == 1) {
        grey.at<std::uint8_t>(map.height - 1 - y, x) = 232;
      }
    }
  }
  return grey;
}

Status WriteSemanticPng(const mapping::MapImage& map, const semantic::SemanticMap& semantic,
                        double scale, const fs::path& path) {
  sim::Bounds bounds;
  const Eigen::Vector2d origin = map.origin.head<2>();
  bounds.Add(origin);
  bounds.Add(origin + map.resolution * Eigen::Vector2d(map.width, map.height));
  sim::DrawingOptions options;
  options.pixels_per_meter = scale;
  Result<sim::TopDownCanvas> canvas = sim::TopDownCanvas::Create(bounds, options);
  if (!canvas.ok()) return canvas.status();
  const semantic::RegionMap regions =
      semantic::SegmentRegions(map, semantic::SemanticMapOptions().chain);
  sim::DrawGreyImage(MapWithRegions(map, regions), origin, map.resolution, *canvas);
  DrawSemanticMap(semantic, *canvas);
  return sim::WritePng(canvas->Compose(), path);
}

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
  if (!args.detector.empty()) {
    Result<std::vector<FrameDetections>> detections = DetectWithModel(args);
    if (!detections.ok()) return detections.status();
    inputs.detections = std::move(*detections);
  }
  inputs.occupancy = *map;
  inputs.trajectory = std::move(*poses);
  inputs.trajectory_source = poses_path.string();
  std::optional<ProgressBar> progress;
  Result<semantic::SemanticMappingResult> result = semantic::MapRun(
      inputs, semantic::SemanticMapOptions(), [&](std::size_t done, std::size_t total) {
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
  semantic::KeyframeDatabase keyframes{fs::absolute(args.run).lexically_normal().string(),
                                       result->keyframes};
  SEMCHAIN_RETURN_IF_ERROR(semantic::WriteKeyframes(out / "keyframes.json", keyframes));
  SEMCHAIN_RETURN_IF_ERROR(WriteSemanticPng(*map, result->map, args.scale, out / "semantic.png"));
  SEMCHAIN_RETURN_IF_ERROR(semantic::WriteSemanticJson(out / "semantic.json", result->map));
  std::size_t links = 0;
  for (const semantic::SemanticChain& chain : result->map.chains) links += chain.links.size();
  std::printf(
      "%d frames, %d detections -> %zu objects, %zu chains (%zu links), %zu neighbour "
      "links, %zu keyframes\nwrote %s\n",
      result->frames, result->detections, result->map.objects.size(), result->map.chains.size(),
      links, result->map.neighbours.size(), result->keyframes.size(),
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
  command->add_option("--detector", args->detector,
                      "YOLOv8-format ONNX model to run on the frames instead of reading "
                      "RUN/detections.jsonl (class names from M.names beside it)");
  command->add_option("--classes", args->classes, "Class-names file of --detector");
  command
      ->add_option("--detector-input", args->detector_input,
                   "Network input WIDTHxHEIGHT of --detector (multiples of 32)")
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
