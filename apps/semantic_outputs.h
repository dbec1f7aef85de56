#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/status.h"
#include "mapping/map_io.h"
#include "semantic/semantic_mapper.h"
#include "sensors/detection.h"

// What `semantic` and `slam --semantic` share: detections by a model instead of
// RUN/detections.jsonl, and the semantic files of a map folder.
namespace semchain::app {

struct DetectorArgs {
  std::string model;  // a YOLOv8-format ONNX model; empty: RUN/detections.jsonl
  std::string classes;
  std::string class_map;       // the model's classes mapped to semchain's (detection/class_map.h)
  std::string input = "auto";  // the model's own (a static export's size), else 640x640
};

// --help of --min-detection-score (`semantic`, `slam --semantic`).
inline constexpr const char* kMinDetectionScoreHelp =
    "Detections scoring lower do not enter the semantic map. The default is the default "
    "model's confidence at its best F1 on a validation split; for a model of your own, take its "
    "confidence_at_best_f1 from `semchain bench detector --split val`";

// Adds --detector, --classes, --class-map and --detector-input to 'command'; 'what' says what the
// model's detections replace (for --help).
void AddDetectorOptions(CLI::App* command, DetectorArgs* args, const std::string& what);

// Detects the frames of a run directory (RUN/camera.yaml, RUN/frames/).
using RunDetectorFunction =
    std::function<Result<std::vector<FrameDetections>>(const std::filesystem::path& run)>;

// The model of 'args' loaded once (its input size, classes and output checked now), as a
// function that detects the frames of any run; 'show_progress' draws a bar per run.
Result<RunDetectorFunction> LoadRunDetector(const DetectorArgs& args, bool show_progress);

// The detections of the run's frames by the model of 'args'.
Result<std::vector<FrameDetections>> DetectWithModel(const DetectorArgs& args,
                                                     const std::filesystem::path& run);

// Draws 'semantic' over 'map' ('scale' pixels per metre, the chains' regions shaded) into the
// PNG 'path', atomically.
Status WriteSemanticPng(const mapping::MapImage& map, const semantic::SemanticMap& semantic,
                        double scale, const std::filesystem::path& path);

// Writes OUT/keyframes.json ('keyframes', e.g. the covering subset of result.keyframes),
// OUT/semantic.png (over 'map', 'scale' pixels per metre) and OUT/semantic.json, each
// atomically, semantic.json last.
Status WriteSemanticOutputs(const std::filesystem::path& out, const mapping::MapImage& map,
                            const semantic::SemanticMappingResult& result,
                            const semantic::KeyframeDatabase& keyframes, double scale);

// "N frames, M detections -> ... K keyframes (of F frames with objects)" for the console, K the
// keyframes written.
std::string SemanticSummary(const semantic::SemanticMappingResult& result,
                            std::size_t keyframes_written);

}  // namespace semchain::app
