#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/status.h"
#include "io/camera_io.h"
#include "io/carmen.h"
#include "io/trajectory_io.h"
#include "sensors/detection.h"

// What `bag export` takes from a run directory (the layout of sim/simulator.h): the scans of
// log.clf with their odometry, truth.txt, camera.yaml, the camera frames and world.yaml. Images
// are not loaded here; each frame says whether its PNGs are there.
namespace semchain::ros1 {

struct CameraFrame {
  std::string name;  // "frames/000123"
  double stamp = 0.0;
  // The frame's detections.jsonl record; absent when the run has no detections.jsonl.
  std::optional<FrameDetections> detections;
  bool has_images = false;  // frames/NNNNNN.png and NNNNNN_depth.png exist
};

struct RunContents {
  std::vector<carmen::Laser> lasers;  // FLASER and ROBOTLASER1 records, in log order
  std::vector<StampedPose> truth;     // empty without truth.txt
  std::optional<CameraInfo> camera;   // camera.yaml
  // The camera frames: detections.jsonl's records when the run has one (it is the run's frame
  // index), else the PNG pairs under frames/ (ListRunFrames' stamps).
  std::vector<CameraFrame> frames;
  std::optional<std::string> world_yaml;

  // The earliest stamp of scans, truth and frames.
  double EarliestStamp() const;
};

// Reads the run in 'run_dir'. A log without scans, an unreadable file, or frames with images
// but no camera.yaml are errors naming the file.
Result<RunContents> LoadRunContents(const std::filesystem::path& run_dir);

}  // namespace semchain::ros1
