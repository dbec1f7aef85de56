#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/status.h"
#include "io/carmen.h"
#include "io/trajectory_io.h"
#include "mapping/incremental_slam.h"
#include "mapping/odometry_repair.h"
#include "mapping/slam_options.h"

// The whole `semchain slam` computation on a sequence of scans: IncrementalSlam fed every scan,
// then a pose for every scan in the final map, then the final map.
namespace semchain::mapping {

// The laser scans of a log with their odometry, each with its own beam geometry (start angle,
// step and beam count may change from scan to scan, as an interlaced laser's do). Errors
// (naming 'source'): no laser lines, a scan without beams; non-increasing timestamps are fine
// (kept as is).
// With 'repair' the odometry steps that move forward while the log's ODOM velocity says the
// robot backs up are reversed (odometry_repair.h) and counted there.
Result<std::vector<StampedScan>> ScansFromLog(const carmen::Log& log, const std::string& source,
                                              ReversedOdometryRepair* repair = nullptr);

// Runs SLAM on 'scans' (at least one). 'progress' (may be empty) is called with the number of
// scans done, out of scans.size() for the filter and as much again for the final passes;
// 'observe' (may be empty) after each scan of the filter.
SlamResult RunSlam(const std::vector<StampedScan>& scans, const SlamOptions& options,
                   const std::function<void(std::size_t)>& progress = {},
                   const std::function<void(const SlamStep&)>& observe = {});

}  // namespace semchain::mapping
