#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/status.h"
#include "io/camera_io.h"
#include "io/trajectory_io.h"
#include "mapping/grid_fusion.h"
#include "mapping/occupancy_grid.h"
#include "mapping/prepared_scan.h"
#include "sensors/depth_to_scan.h"
#include "sensors/detection.h"

// Depth camera + lidar fusion (seed 004 §2, DESIGN.md §3.3): every depth frame of a run becomes
// a virtual scan (eq. 6–8), placed at the SLAM pose of its timestamp and integrated into a depth
// occupancy grid, which is then fused with the lidar grid cell by cell (eq. 10).
namespace semchain::mapping {

struct DepthMappingOptions {
  DepthToScanOptions scan;
  // The virtual scans' ranges end at the camera's max_range; a bin without a point in the band
  // marks nothing (the floor there could hide a hole as well as be free).
  ScanPreparationOptions preparation;
  GridFusionOptions fusion;
  // A frame takes the trajectory pose whose timestamp is within this of its own; simulated
  // frames share the timestamps of laser scans, so poses are exact.
  double stamp_tolerance_seconds = 1e-3;

  bool Validate(std::string* error) const;
};

// What a run directory says about its depth camera: RUN/camera.yaml and the frame list with
// stamps (RUN/detections.jsonl). Reading it checks only those two files.
struct DepthRun {
  std::filesystem::path run_dir;
  CameraInfo camera;
  std::vector<FrameDetections> frames;
};
Result<DepthRun> LoadDepthRun(const std::filesystem::path& run_dir);

// The pose of 'trajectory' (sorted by timestamp) nearest to 'stamp' when within 'tolerance'.
// The error says which span the trajectory covers.
Result<Pose2> PoseAtStamp(const std::vector<StampedPose>& trajectory, double stamp,
                          double tolerance);

struct DepthFusionResult {
  OccupancyGrid depth;  // from the depth frames only
  OccupancyGrid fused;  // eq. 10 of the lidar grid and 'depth'
  std::size_t frames = 0;
};

// Builds the depth grid of 'run' (same options and origin as 'lidar') with the frames posed by
// 'trajectory' (any order, e.g. the SLAM trajectory: a pose per scan), and fuses it
// with 'lidar'. Errors: a frame whose stamp the trajectory does not cover, a missing or
// unreadable depth image (named). 'progress' (may be empty) gets the number of frames done.
Result<DepthFusionResult> FuseDepthRun(const DepthRun& run, const OccupancyGrid& lidar,
                                       const std::vector<StampedPose>& trajectory,
                                       const DepthMappingOptions& options = {},
                                       const std::function<void(std::size_t)>& progress = {});

}  // namespace semchain::mapping
