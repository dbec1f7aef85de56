#include "semantic/semantic_run.h"

#include <algorithm>
#include <cstdio>

#include "io/camera_io.h"
#include "io/detections_io.h"
#include "io/rgbd_frame_io.h"
#include "io/trajectory_lookup.h"

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

Result<SemanticMappingResult> MapRun(
    const SemanticRunInputs& inputs, const SemanticMapOptions& options,
    const std::function<void(std::size_t, std::size_t)>& progress) {
  std::string invalid;
  if (!options.Validate(&invalid)) return Status::Error("invalid semantic options: " + invalid);
  const fs::path& run = inputs.run_dir;
  Result<CameraInfo> camera = ReadCameraYaml(run / "camera.yaml");
  if (!camera.ok()) return camera.status();

  std::vector<FrameDetections> frames;
  const fs::path detections_path = run / "detections.jsonl";
  if (inputs.detections) {
    frames = *inputs.detections;
  } else {
    Result<std::vector<FrameDetections>> read = ReadDetectionsJsonl(detections_path);
    if (!read.ok()) return read.status();
    frames = std::move(*read);
  }
  const std::string source =
      inputs.detections ? std::string("the detector's output") : detections_path.string();
  std::size_t detection_count = 0;
  for (const FrameDetections& frame : frames) detection_count += frame.detections.size();
  if (detection_count == 0) {
    return Status::Error(source + ": no detections in " + std::to_string(frames.size()) +
                         " frames: nothing to put on the map");
  }
  if (inputs.trajectory.empty()) return Status::Error(inputs.trajectory_source + ": no poses");

  // Every frame must have its depth image and lie inside the trajectory.
  const TrajectoryLookup lookup(inputs.trajectory);
  double first = inputs.trajectory.front().timestamp;
  double last = first;
  for (const StampedPose& pose : inputs.trajectory) {
    first = std::min(first, pose.timestamp);
    last = std::max(last, pose.timestamp);
  }
  std::vector<Pose2> poses;
  for (const FrameDetections& frame : frames) {
    std::error_code error;
    if (!fs::is_regular_file(DepthImagePath(run, frame.frame), error)) {
      return Status::Error(source + ": frame " + frame.frame + " has no depth image " +
                           DepthImagePath(run, frame.frame).string());
    }
    const std::optional<Pose2> pose =
        lookup.At(frame.stamp, options.pose_tolerance, options.max_pose_gap);
    if (!pose) {
      return Status::Error(source + ": frame " + frame.frame + " at " + Seconds(frame.stamp) +
                           " is not covered by " + inputs.trajectory_source + " (" +
                           Seconds(first) + " to " + Seconds(last) + ")");
    }
    poses.push_back(*pose);
  }

  const PinholeCamera& k = camera->camera.intrinsics;
  SemanticMapper mapper(inputs.occupancy,
                        inputs.classes.empty() ? ClassesOf(frames) : inputs.classes, camera->camera,
                        options);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    Result<cv::Mat> depth = ReadDepthImage(DepthImagePath(run, frames[i].frame),
                                           camera->depth_scale, cv::Size(k.width, k.height));
    if (!depth.ok()) return depth.status();
    mapper.AddFrame(frames[i], poses[i], *depth);
    if (progress) progress(i + 1, frames.size());
  }
  return mapper.Finish();
}

}  // namespace semchain::semantic
