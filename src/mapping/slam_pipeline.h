#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/status.h"
#include "io/carmen.h"
#include "io/trajectory_io.h"
#include "mapping/laser_odometry.h"
#include "mapping/occupancy_grid.h"
#include "mapping/rbpf_slam.h"
#include "mapping/scan_localizer.h"

// The whole `semchain slam` computation on a sequence of scans: RBPF SLAM, then a pose for
// every scan in the final map, then the final map.
namespace semchain::mapping {

struct SlamOptions {
  LaserOdometryOptions laser_odometry;
  RbpfOptions rbpf;
  EveryScanOptions every_scan;

  bool Validate(std::string* error) const;
};

struct SlamResult {
  OccupancyGrid map;                    // built from the final poses
  std::vector<StampedPose> trajectory;  // one pose per scan, in log order
  std::vector<int> processed;           // indices of the scans the RBPF processed
  int localized = 0;                    // scans refined by scan matching in the final map
  int laser_odometry_rejected = 0;      // scans that kept their wheel odometry increment
  RbpfStatistics statistics;
  // Wall time of each stage, seconds.
  double laser_odometry_seconds = 0.0;
  double filter_seconds = 0.0;
  double every_scan_seconds = 0.0;
};

// The laser scans of a log with their odometry. Errors (naming 'source'): no laser lines,
// beam counts that change within the log, non-increasing timestamps are fine (kept as is).
Result<std::vector<StampedScan>> ScansFromLog(const carmen::Log& log, const std::string& source);

// What a caller sees of the filter after each scan, while SLAM runs (live semantic mapping).
struct SlamStep {
  std::size_t scan = 0;    // index of the scan just added
  bool processed = false;  // the filter updated on it (the best particle may have changed)
  const RbpfSlam* slam = nullptr;
  const std::vector<StampedScan>* scans = nullptr;  // the odometry the filter uses
};

// The best particle's trajectory over the first 'count' scans of 'scans' (count ≥ 1): its
// poses at the scans it processed, odometry re-anchored on them in between (as the final
// trajectory is made before the every-scan pass).
std::vector<StampedPose> CurrentTrajectory(const std::vector<StampedScan>& scans, std::size_t count,
                                           const RbpfSlam& slam);

// Runs SLAM on 'scans' (at least one). 'progress' (may be empty) is called with the number of
// scans done, out of scans.size() for the filter and as much again for the final passes;
// 'observe' (may be empty) after each scan of the filter.
SlamResult RunSlam(const std::vector<StampedScan>& scans, const SlamOptions& options,
                   const std::function<void(std::size_t)>& progress = {},
                   const std::function<void(const SlamStep&)>& observe = {});

}  // namespace semchain::mapping
