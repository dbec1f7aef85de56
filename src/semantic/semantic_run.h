#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/status.h"
#include "io/camera_io.h"
#include "io/trajectory_io.h"
#include "mapping/map_io.h"
#include "semantic/semantic_mapper.h"
#include "sensors/detection.h"

// Semantic mapping of a whole run directory (DESIGN.md §1: run/ + map/ → map/semantic.json):
// RUN/camera.yaml, RUN/detections.jsonl (or detections given by a detector), the depth frames,
// and the SLAM trajectory that poses every frame.
namespace semchain::semantic {

struct SemanticRunInputs {
  std::filesystem::path run_dir;
  mapping::MapImage occupancy;
  std::vector<StampedPose> trajectory;
  std::string trajectory_source = "trajectory";  // for error messages
  // Detections to use instead of RUN/detections.jsonl (e.g. from `--detector`).
  std::optional<std::vector<FrameDetections>> detections;
  // The class order of the layers: DefaultClassNames() and then any other class met, unless
  // set here.
  std::vector<std::string> classes;
};

// A run's camera and frames, checked: camera.yaml readable, every frame's depth image present,
// at least one detection.
struct RunFrames {
  CameraInfo camera;
  std::vector<FrameDetections> frames;
  std::vector<std::string> classes;  // as SemanticRunInputs::classes says
  std::string source;                // where the detections come from, for messages
};

// 'detections' and 'classes' as in SemanticRunInputs.
Result<RunFrames> LoadRunFrames(const std::filesystem::path& run_dir,
                                const std::optional<std::vector<FrameDetections>>& detections,
                                const std::vector<std::string>& classes);

// The depth image of 'frame' in metres (CV_32FC1, the camera's size).
Result<cv::Mat> ReadFrameDepth(const std::filesystem::path& run_dir, const RunFrames& run,
                               const FrameDetections& frame);

// Checks everything before mapping anything, so that a bad run fails fast with one message:
// camera.yaml readable, every frame's depth image present, every frame inside the trajectory,
// at least one detection. 'progress' (may be empty) is called with the frames done.
Result<SemanticMappingResult> MapRun(
    const SemanticRunInputs& inputs, const SemanticMapOptions& options,
    const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace semchain::semantic
