#include "mapping/depth_mapping.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/detections_io.h"
#include "io/rgbd_frame_io.h"
#include "mapping/ray_casting.h"

namespace semchain::mapping {

bool DepthMappingOptions::Validate(std::string* error) const {
  if (!scan.Validate(error) || !preparation.Validate(error) || !fusion.Validate(error)) {
    return false;
  }
  if (!(stamp_tolerance_seconds >= 0.0)) {
    *error = "stamp_tolerance_seconds must be >= 0";
    return false;
  }
  return true;
}

Result<DepthRun> LoadDepthRun(const std::filesystem::path& run_dir) {
  DepthRun run;
  run.run_dir = run_dir;
  Result<CameraInfo> camera = ReadCameraYaml(run_dir / "camera.yaml");
  if (!camera.ok()) return camera.status();
  run.camera = *camera;
  Result<std::vector<FrameDetections>> frames = ReadDetectionsJsonl(run_dir / "detections.jsonl");
  if (!frames.ok()) return frames.status();
  run.frames = std::move(*frames);
  if (run.frames.empty()) {
    return Status::Error((run_dir / "detections.jsonl").string() + ": lists no camera frames");
  }
  return run;
}

Result<Pose2> PoseAtStamp(const std::vector<StampedPose>& trajectory, double stamp,
                          double tolerance) {
  if (trajectory.empty()) return Status::Error("the trajectory is empty");
  const auto after =
      std::lower_bound(trajectory.begin(), trajectory.end(), stamp,
                       [](const StampedPose& pose, double t) { return pose.timestamp < t; });
  const StampedPose* best = nullptr;
  if (after != trajectory.end()) best = &*after;
  if (after != trajectory.begin()) {
    const StampedPose& before = *(after - 1);
    if (best == nullptr || stamp - before.timestamp < best->timestamp - stamp) best = &before;
  }
  if (std::abs(best->timestamp - stamp) > tolerance) {
    char message[160];
    std::snprintf(message, sizeof(message),
                  "stamp %.6f s is not covered by the trajectory (%zu poses, %.6f to %.6f s, "
                  "nearest %.6f s)",
                  stamp, trajectory.size(), trajectory.front().timestamp,
                  trajectory.back().timestamp, best->timestamp);
    return Status::Error(message);
  }
  return best->pose;
}

Result<DepthFusionResult> FuseDepthRun(const DepthRun& run, const OccupancyGrid& lidar,
                                       const std::vector<StampedPose>& trajectory,
                                       const DepthMappingOptions& options,
                                       const std::function<void(std::size_t)>& progress) {
  std::vector<StampedPose> sorted = trajectory;
  std::stable_sort(sorted.begin(), sorted.end(), [](const StampedPose& a, const StampedPose& b) {
    return a.timestamp < b.timestamp;
  });
  const MountedCamera& camera = run.camera.camera;
  const DepthToScanConverter converter(camera, options.scan);
  ScanPreparationOptions preparation = options.preparation;
  preparation.max_range_meters = std::min(preparation.max_range_meters, camera.max_range);
  OccupancyGrid depth(lidar.options(), lidar.origin());
  const cv::Size image_size(camera.intrinsics.width, camera.intrinsics.height);
  const std::string jsonl = (run.run_dir / "detections.jsonl").string();
  // Every frame's pose first: a trajectory that misses a frame fails before any image is read.
  std::vector<Pose2> poses;
  for (const FrameDetections& frame : run.frames) {
    const Result<Pose2> pose = PoseAtStamp(sorted, frame.stamp, options.stamp_tolerance_seconds);
    if (!pose.ok()) return pose.status().WithContext(jsonl + ": frame " + frame.frame);
    poses.push_back(*pose);
  }
  for (std::size_t i = 0; i < run.frames.size(); ++i) {
    const FrameDetections& frame = run.frames[i];
    const Result<cv::Mat> image = ReadDepthImage(DepthImagePath(run.run_dir, frame.frame),
                                                 run.camera.depth_scale, image_size);
    if (!image.ok()) return image.status();
    const LaserScan scan = converter.Convert(*image, frame.stamp);
    InsertScan(PrepareScan(scan, converter.robot_from_scan(), preparation), poses[i], &depth);
    if (progress) progress(i + 1);
  }
  DepthFusionResult result{depth, FuseGrids(lidar, depth, options.fusion), run.frames.size()};
  return result;
}

}  // namespace semchain::mapping
