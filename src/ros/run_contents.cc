#include "ros/run_contents.h"

#include <algorithm>
#include <limits>
#include <system_error>

#include "core/atomic_file.h"
#include "detection/run_detection.h"
#include "io/detections_io.h"
#include "io/rgbd_frame_io.h"

namespace semchain::ros1 {
namespace fs = std::filesystem;
namespace {

bool IsFile(const fs::path& path) {
  std::error_code error;
  return fs::is_regular_file(path, error);
}

Status LoadLasers(const fs::path& run_dir, RunContents* run) {
  const fs::path path = IsFile(run_dir / "log.clf.gz") && !IsFile(run_dir / "log.clf")
                            ? run_dir / "log.clf.gz"
                            : run_dir / "log.clf";
  Result<carmen::Log> log = carmen::ReadLog(path);
  if (!log.ok()) return log.status();
  for (const carmen::Laser* laser : log->Lasers()) run->lasers.push_back(*laser);
  if (run->lasers.empty()) {
    return Status::Error(path.string() + ": no laser scans (FLASER or ROBOTLASER1 lines)");
  }
  return Status::Ok();
}

// The frames of the run: detections.jsonl's records, or the PNG pairs without detections.
Status LoadFrames(const fs::path& run_dir, RunContents* run) {
  if (IsFile(run_dir / "detections.jsonl")) {
    Result<std::vector<FrameDetections>> records =
        ReadDetectionsJsonl(run_dir / "detections.jsonl");
    if (!records.ok()) return records.status();
    for (FrameDetections& record : *records) {
      CameraFrame frame{record.frame, record.stamp, std::move(record), false};
      run->frames.push_back(std::move(frame));
    }
  } else if (run->camera && fs::is_directory(run_dir / "frames")) {
    Result<std::vector<detection::RunFrame>> listed =
        detection::ListRunFrames(run_dir, *run->camera);
    if (!listed.ok()) return listed.status();
    for (const detection::RunFrame& listed_frame : *listed) {
      run->frames.push_back({listed_frame.frame, listed_frame.stamp, std::nullopt, false});
    }
  }
  for (CameraFrame& frame : run->frames) {
    frame.has_images =
        IsFile(ColorImagePath(run_dir, frame.name)) && IsFile(DepthImagePath(run_dir, frame.name));
    if (frame.has_images && !run->camera) {
      return Status::Error((run_dir / "camera.yaml").string() +
                           ": missing, and the run has frames (" + frame.name + ")");
    }
  }
  return Status::Ok();
}

}  // namespace

double RunContents::EarliestStamp() const {
  double earliest = std::numeric_limits<double>::infinity();
  for (const carmen::Laser& laser : lasers) earliest = std::min(earliest, laser.stamp.timestamp);
  for (const StampedPose& pose : truth) earliest = std::min(earliest, pose.timestamp);
  for (const CameraFrame& frame : frames) earliest = std::min(earliest, frame.stamp);
  return earliest;
}

Result<RunContents> LoadRunContents(const fs::path& run_dir) {
  std::error_code error;
  if (!fs::is_directory(run_dir, error)) {
    return Status::Error(run_dir.string() + ": no such run directory");
  }
  RunContents run;
  SEMCHAIN_RETURN_IF_ERROR(LoadLasers(run_dir, &run));
  if (IsFile(run_dir / "truth.txt")) {
    Result<std::vector<StampedPose>> truth = ReadTrajectory(run_dir / "truth.txt");
    if (!truth.ok()) return truth.status();
    run.truth = std::move(*truth);
  }
  if (IsFile(run_dir / "camera.yaml")) {
    Result<CameraInfo> camera = ReadCameraYaml(run_dir / "camera.yaml");
    if (!camera.ok()) return camera.status();
    run.camera = *camera;
  }
  SEMCHAIN_RETURN_IF_ERROR(LoadFrames(run_dir, &run));
  if (IsFile(run_dir / "world.yaml")) {
    Result<std::string> world = ReadFile(run_dir / "world.yaml");
    if (!world.ok()) return world.status();
    run.world_yaml = std::move(*world);
  }
  return run;
}

}  // namespace semchain::ros1
