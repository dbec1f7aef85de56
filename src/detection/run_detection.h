#pragma once

#include <filesystem>
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/status.h"
#include "detection/box_depth.h"
#include "detection/detector.h"
#include "io/camera_io.h"
#include "sensors/detection.h"

// A detector run over the RGB-D frames of a run directory (`semchain simulate` layout:
// RUN/camera.yaml, RUN/frames/NNNNNN.png and NNNNNN_depth.png), giving detections.jsonl records
// that feed the semantic map exactly as the simulator's do.
namespace semchain::detection {

struct RunFrame {
  std::string frame;  // "frames/000123": the RGB/depth pair without extension
  double stamp = 0.0;
};

// True when 'dir' has camera.yaml and a frames/ directory.
bool IsRunDirectory(const std::filesystem::path& dir);

// The colour frames of 'run_dir' (frames/*.png that are not *_depth.png) in name order. The
// simulator records frame times only in RUN/detections.jsonl, so a frame named there gets its
// stamp; otherwise frame k gets k / camera.frame_rate_hz.
Result<std::vector<RunFrame>> ListRunFrames(const std::filesystem::path& run_dir,
                                            const CameraInfo& camera);

struct RunDetectionOptions {
  BoxDepthOptions depth;
  // A detection whose box core has too few depth readings is dropped (the simulator reports no
  // object without depth); true keeps it with depth_m = 0.
  bool keep_without_depth = false;
  bool show_progress = false;  // a progress bar on stderr when it is a terminal
};

// Gives each detection the depth of its box in 'depth_m' (CV_32FC1 metres, aligned to the colour
// image; BoxDepth, 'camera' telling the floor, may be null); detections without depth are
// dropped unless options.keep_without_depth.
void MeasureDepths(const cv::Mat& depth_m, const MountedCamera* camera,
                   const RunDetectionOptions& options, std::vector<Detection>& detections);

// Called after each frame with its colour image (RGB) and its detections; an error stops the
// run and is returned.
using FrameSink = std::function<Status(const cv::Mat& rgb, const FrameDetections& frame)>;

// Runs 'detector' over every colour frame of 'run_dir' (ListRunFrames) and gives each detection
// the depth of its box from the aligned depth frame (BoxDepth, metres, camera.yaml's
// depth_scale). One FrameDetections per frame, in frame order, named as the simulator names
// them; an unreadable camera.yaml or frame, a depth image of another size or a detector
// failure is an error naming the file.
Result<std::vector<FrameDetections>> DetectRunFrames(Detector& detector,
                                                     const std::filesystem::path& run_dir,
                                                     const RunDetectionOptions& options = {},
                                                     const FrameSink& sink = {});

}  // namespace semchain::detection
