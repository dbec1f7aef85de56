#include "semantic/semantic_run.h"

#include <algorithm>
#include <cstdio>

#include "io/camera_io.h"
#include "io/detections_io.h"
#include "io/rgbd_frame_io.h"
#include "io/trajectory_lookup.h"
#include "semantic/semantic_chain.h"

namespace semchain::semantic {
namespace fs = std::filesystem;
namespace {

std::string Seconds(double t) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f s", t);
  return text;
}

std::vector<std::string> ClassesOf(const std::vector<FrameDetections>& frames) {
  std::vector<std::string> classes = DefaultClassNames();
  for (const FrameDetections& frame : frames) {
    for (const Detection& detection : frame.detections) {
      if (std::find(classes.begin(), classes.end(), detection.class_name) == classes.end()) {
        classes.push_back(detection.class_name);
      }
    }
  }
  return classes;
}

}  // namespace

Result<RunFrames> LoadRunFrames(const fs::path& run,
                                const std::optional<std::vector<FrameDetections>>& detections,
                                const std::vector<std::string>& classes) {
  Result<CameraInfo> camera = ReadCameraYaml(run / "camera.yaml");
  if (!camera.ok()) return camera.status();
  RunFrames loaded;
  loaded.camera = *camera;
  const fs::path detections_path = run / "detections.jsonl";
  if (detections) {
    loaded.frames = *detections;
  } else {
    Result<std::vector<FrameDetections>> read = ReadDetectionsJsonl(detections_path);
    if (!read.ok()) return read.status();
    loaded.frames = std::move(*read);
  }
  loaded.source = detections ? std::string("the detector's output") : detections_path.string();
  std::size_t detection_count = 0;
  for (const FrameDetections& frame : loaded.frames) detection_count += frame.detections.size();
  if (detection_count == 0) {
    return Status::Error(loaded.source + ": no detections in " +
                         std::to_string(loaded.frames.size()) +
                         " frames: nothing to put on the map");
  }
  for (const FrameDetections& frame : loaded.frames) {
    std::error_code error;
    if (!fs::is_regular_file(DepthImagePath(run, frame.frame), error)) {
      return Status::Error(loaded.source + ": frame " + frame.frame + " has no depth image " +
                           DepthImagePath(run, frame.frame).string());
    }
  }
  loaded.classes = classes.empty() ? ClassesOf(loaded.frames) : classes;
  return loaded;
}

Result<cv::Mat> ReadFrameDepth(const fs::path& run_dir, const RunFrames& run,
                               const FrameDetections& frame) {
  const PinholeCamera& k = run.camera.camera.intrinsics;
  return ReadDepthImage(DepthImagePath(run_dir, frame.frame), run.camera.depth_scale,
                        cv::Size(k.width, k.height));
}

Result<SemanticMappingResult> MapRun(
    const SemanticRunInputs& inputs, const SemanticMapOptions& options,
    const std::function<void(std::size_t, std::size_t)>& progress) {
  std::string invalid;
  if (!options.Validate(&invalid)) return Status::Error("invalid semantic options: " + invalid);
  Result<RunFrames> run = LoadRunFrames(inputs.run_dir, inputs.detections, inputs.classes);
  if (!run.ok()) return run.status();
  if (inputs.trajectory.empty()) return Status::Error(inputs.trajectory_source + ": no poses");

  // Every frame must lie inside the trajectory.
  const TrajectoryLookup lookup(inputs.trajectory);
  double first = inputs.trajectory.front().timestamp;
  double last = first;
  for (const StampedPose& pose : inputs.trajectory) {
    first = std::min(first, pose.timestamp);
    last = std::max(last, pose.timestamp);
  }
  std::vector<Pose2> poses;
  for (const FrameDetections& frame : run->frames) {
    const std::optional<Pose2> pose =
        lookup.At(frame.stamp, options.pose_tolerance, options.max_pose_gap);
    if (!pose) {
      return Status::Error(run->source + ": frame " + frame.frame + " at " + Seconds(frame.stamp) +
                           " is not covered by " + inputs.trajectory_source + " (" +
                           Seconds(first) + " to " + Seconds(last) + ")");
    }
    poses.push_back(*pose);
  }

  SemanticMapper mapper(GeometryOf(inputs.occupancy), run->classes, run->camera.camera, options);
  for (std::size_t i = 0; i < run->frames.size(); ++i) {
    Result<cv::Mat> depth = ReadFrameDepth(inputs.run_dir, *run, run->frames[i]);
    if (!depth.ok()) return depth.status();
    mapper.AddFrame(run->frames[i], poses[i], *depth);
    if (progress) progress(i + 1, run->frames.size());
  }
  return mapper.Snapshot(inputs.occupancy);
}

}  // namespace semchain::semantic
