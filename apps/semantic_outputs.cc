#include "apps/semantic_outputs.h"

#include <cstdio>
#include <memory>

#include "apps/map_grey.h"
#include "apps/semantic_drawing.h"
#include "apps/shipped_file.h"
#include "detection/run_detection.h"
#include "detection/yolo_detector.h"
#include "drawing/canvas.h"
#include "drawing/plots.h"
#include "drawing/png.h"
#include "semantic/keyframes.h"
#include "semantic/semantic_chain.h"
#include "semantic/semantic_map_io.h"

namespace semchain::app {
namespace {

namespace fs = std::filesystem;

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

}  // namespace

Status WriteSemanticPng(const mapping::MapImage& map, const semantic::SemanticMap& semantic,
                        double scale, const fs::path& path) {
  drawing::Bounds bounds;
  const Eigen::Vector2d origin = map.origin.head<2>();
  bounds.Add(origin);
  bounds.Add(origin + map.resolution * Eigen::Vector2d(map.width, map.height));
  drawing::DrawingOptions options;
  options.pixels_per_meter = scale;
  Result<drawing::TopDownCanvas> canvas = drawing::TopDownCanvas::Create(bounds, options);
  if (!canvas.ok()) return canvas.status();
  const semantic::RegionMap regions =
      semantic::SegmentRegions(map, semantic::SemanticMapOptions().chain);
  drawing::DrawGreyImage(MapWithRegions(map, regions), origin, map.resolution, *canvas);
  DrawSemanticMap(semantic, *canvas);
  return drawing::WritePng(canvas->Compose(), path);
}

void AddDetectorOptions(CLI::App* command, DetectorArgs* args, const std::string& what) {
  command
      ->add_option("--detector", args->model,
                   "YOLOv8-format ONNX model run on the rendered frames instead of " + what +
                       " (class names from M.names beside it)")
      ->transform(ShippedFile());
  command->add_option("--classes", args->classes, "Class-names file of --detector")
      ->transform(ShippedFile());
  command
      ->add_option("--class-map", args->class_map,
                   "YAML map 'model class: semchain class' of --detector's classes (e.g. "
                   "config/classes/coco.yaml); the classes it does not name are dropped")
      ->needs("--detector");
  command
      ->add_option(
          "--detector-input", args->input,
          "Network input WIDTHxHEIGHT of --detector (multiples of 32), or auto: its export size")
      ->capture_default_str();
}

Result<RunDetectorFunction> LoadRunDetector(const DetectorArgs& args, bool show_progress) {
  detection::YoloOptions options;
  SEMCHAIN_RETURN_IF_ERROR(detection::ParseInputSize(args.input, &options));
  std::string invalid;
  if (!options.Validate(&invalid)) return Status::Error("--detector-input: " + invalid);
  Result<std::unique_ptr<detection::YoloDetector>> loaded =
      detection::LoadYoloDetector(args.model, args.classes, options, args.class_map);
  if (!loaded.ok()) return loaded.status();
  // std::function must be copyable: the detector is shared by the copies.
  std::shared_ptr<detection::YoloDetector> detector = std::move(*loaded);
  detection::RunDetectionOptions run_options;
  run_options.show_progress = show_progress;
  return RunDetectorFunction([detector, run_options](const fs::path& run) {
    return detection::DetectRunFrames(*detector, run, run_options);
  });
}

Result<std::vector<FrameDetections>> DetectWithModel(const DetectorArgs& args,
                                                     const fs::path& run) {
  Result<RunDetectorFunction> detect = LoadRunDetector(args, /*show_progress=*/true);
  if (!detect.ok()) return detect.status();
  return (*detect)(run);
}

Status WriteSemanticOutputs(const fs::path& out, const mapping::MapImage& map,
                            const semantic::SemanticMappingResult& result,
                            const semantic::KeyframeDatabase& keyframes, double scale) {
  SEMCHAIN_RETURN_IF_ERROR(semantic::WriteKeyframes(out / "keyframes.json", keyframes));
  SEMCHAIN_RETURN_IF_ERROR(WriteSemanticPng(map, result.map, scale, out / "semantic.png"));
  return semantic::WriteSemanticJson(out / "semantic.json", result.map);
}

std::string SemanticSummary(const semantic::SemanticMappingResult& result,
                            std::size_t keyframes_written) {
  std::size_t links = 0;
  for (const semantic::SemanticChain& chain : result.map.chains) links += chain.links.size();
  char text[256];
  std::snprintf(text, sizeof(text),
                "%d frames, %d detections -> %zu objects, %zu chains (%zu links), %zu neighbour "
                "links, %zu keyframes (of %zu frames with objects)",
                result.frames, result.detections, result.map.objects.size(),
                result.map.chains.size(), links, result.map.neighbours.size(), keyframes_written,
                result.keyframes.size());
  return text;
}

}  // namespace semchain::app
