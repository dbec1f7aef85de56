#include "detection/run_detection.h"

#include <algorithm>
#include <map>
#include <system_error>

#include "core/progress_bar.h"
#include "io/detections_io.h"
#include "io/rgbd_frame_io.h"

namespace semchain::detection {
namespace fs = std::filesystem;
namespace {

constexpr std::string_view kDepthSuffix = "_depth";

// Frame name -> stamp from RUN/detections.jsonl, when the run has one.
Result<std::map<std::string, double>> RecordedStamps(const fs::path& run_dir) {
  std::map<std::string, double> stamps;
  std::error_code ec;
  if (!fs::is_regular_file(run_dir / "detections.jsonl", ec)) return stamps;
  Result<std::vector<FrameDetections>> recorded = ReadDetectionsJsonl(run_dir / "detections.jsonl");
  if (!recorded.ok()) return recorded.status();
  for (const FrameDetections& frame : *recorded) stamps[frame.frame] = frame.stamp;
  return stamps;
}

}  // namespace

void MeasureDepths(const cv::Mat& depth_m, const MountedCamera* camera,
                   const RunDetectionOptions& options, std::vector<Detection>& detections) {
  std::vector<Detection> kept;
  for (Detection& detection : detections) {
    const std::optional<double> depth = BoxDepth(depth_m, detection.box, camera, options.depth);
    if (!depth && !options.keep_without_depth) continue;
    detection.depth_m = depth.value_or(0.0);
    kept.push_back(std::move(detection));
  }
  detections = std::move(kept);
}

bool IsRunDirectory(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / "camera.yaml", ec) && fs::is_directory(dir / "frames", ec);
}

Result<std::vector<RunFrame>> ListRunFrames(const fs::path& run_dir, const CameraInfo& camera) {
  std::vector<std::string> stems;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(run_dir / "frames", ec)) {
    const fs::path& path = entry.path();
    const std::string stem = path.stem().string();
    const bool depth =
        stem.size() >= kDepthSuffix.size() &&
        stem.compare(stem.size() - kDepthSuffix.size(), kDepthSuffix.size(), kDepthSuffix) == 0;
    if (path.extension() == ".png" && !depth) stems.push_back(stem);
  }
  if (ec) return Status::Error((run_dir / "frames").string() + ": " + ec.message());
  std::sort(stems.begin(), stems.end());
  Result<std::map<std::string, double>> stamps = RecordedStamps(run_dir);
  if (!stamps.ok()) return stamps.status();
  std::vector<RunFrame> frames;
  for (std::size_t k = 0; k < stems.size(); ++k) {
    RunFrame frame{"frames/" + stems[k], double(k) / camera.frame_rate_hz};
    const auto recorded = stamps->find(frame.frame);
    if (recorded != stamps->end()) frame.stamp = recorded->second;
    frames.push_back(std::move(frame));
  }
  return frames;
}

Result<std::vector<FrameDetections>> DetectRunFrames(Detector& detector, const fs::path& run_dir,
                                                     const RunDetectionOptions& options,
                                                     const FrameSink& sink) {
  std::string error;
  if (!options.depth.Validate(&error)) return Status::Error("depth options: " + error);
  Result<CameraInfo> camera = ReadCameraYaml(run_dir / "camera.yaml");
  if (!camera.ok()) return camera.status();
  Result<std::vector<RunFrame>> frames = ListRunFrames(run_dir, *camera);
  if (!frames.ok()) return frames.status();
  const cv::Size size(camera->camera.intrinsics.width, camera->camera.intrinsics.height);
  std::vector<FrameDetections> results;
  std::optional<ProgressBar> progress;
  if (options.show_progress) progress.emplace("detect", frames->size());
  for (const RunFrame& frame : *frames) {
    Result<cv::Mat> rgb = ReadColorImage(ColorImagePath(run_dir, frame.frame));
    if (!rgb.ok()) return rgb.status();
    Result<cv::Mat> depth =
        ReadDepthImage(DepthImagePath(run_dir, frame.frame), camera->depth_scale, rgb->size());
    if (!depth.ok()) return depth.status();
    if (rgb->size() != size) {
      return Status::Error(ColorImagePath(run_dir, frame.frame).string() +
                           ": image size differs from camera.yaml");
    }
    Result<std::vector<Detection>> detections = detector.Detect(*rgb);
    if (!detections.ok()) return detections.status().WithContext(frame.frame);
    FrameDetections result{frame.frame, frame.stamp, std::move(*detections)};
    MeasureDepths(*depth, &camera->camera, options, result.detections);
    if (sink) SEMCHAIN_RETURN_IF_ERROR(sink(*rgb, result));
    results.push_back(std::move(result));
    if (progress) progress->Update(results.size());
  }
  if (progress) progress->Finish();
  return results;
}

}  // namespace semchain::detection
