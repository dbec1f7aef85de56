#include "mapping/slam_pipeline.h"

#include <atomic>
#include <chrono>

#include "core/check.h"
#include "mapping/parallel_for.h"
#include "mapping/ray_casting.h"

namespace semchain::mapping {
namespace {

// The pose of each of the first 'count' scans from the best particle's trajectory
// (interpolated odometry between its processed scans).
std::vector<Pose2> InterpolatedPoses(const std::vector<StampedScan>& scans, std::size_t count,
                                     const Particle& best, std::vector<int>* processed) {
  std::vector<Pose2> odometry;
  std::vector<double> timestamps;
  for (std::size_t i = 0; i < count; ++i) {
    odometry.push_back(scans[i].odometry);
    timestamps.push_back(scans[i].scan.timestamp);
  }
  std::vector<std::pair<int, Pose2>> corrected;
  for (const TrajectoryNode* node : Unroll(best.trajectory)) {
    corrected.emplace_back(node->scan_index, node->pose);
    processed->push_back(node->scan_index);
  }
  return InterpolateTrajectory(odometry, timestamps, corrected);
}

OccupancyGrid BuildMap(const std::vector<PreparedScan>& scans, const std::vector<Pose2>& poses,
                       const OccupancyGridOptions& options) {
  OccupancyGrid map(options);
  for (std::size_t i = 0; i < scans.size(); ++i) InsertScan(scans[i], poses[i], &map);
  return map;
}

// Localizes every scan in 'map' from 'poses' (updated in place); returns how many matched.
int LocalizeAll(const OccupancyGrid& map, const std::vector<PreparedScan>& scans,
                const SlamOptions& options, std::vector<Pose2>* poses,
                const std::function<void(std::size_t)>& tick) {
  const LikelihoodField field(map, options.rbpf.field);
  std::atomic<int> matched{0};
  std::atomic<std::size_t> done{0};
  ParallelFor(static_cast<int>(scans.size()), ResolveThreadCount(options.rbpf.threads), [&](int i) {
    const LocalizationResult result =
        LocalizeScan(field, scans[i], (*poses)[i], options.every_scan);
    (*poses)[i] = result.pose;
    if (result.matched) ++matched;
    ++done;
  });
  if (tick) tick(done.load());
  return matched.load();
}

}  // namespace

std::vector<StampedPose> CurrentTrajectory(const std::vector<StampedScan>& scans, std::size_t count,
                                           const RbpfSlam& slam) {
  SEMCHAIN_CHECK(count >= 1 && count <= scans.size());
  std::vector<int> processed;
  const std::vector<Pose2> poses = InterpolatedPoses(scans, count, slam.BestParticle(), &processed);
  std::vector<StampedPose> trajectory;
  trajectory.reserve(count);
  for (std::size_t i = 0; i < count; ++i) trajectory.push_back({scans[i].scan.timestamp, poses[i]});
  return trajectory;
}

bool SlamOptions::Validate(std::string* error) const {
  if (!rbpf.Validate(error)) return false;
  if (!laser_odometry.Validate(error)) {
    *error = "laser_odometry." + *error;
    return false;
  }
  if (every_scan.Validate(error)) return true;
  *error = "every_scan." + *error;
  return false;
}

Result<std::vector<StampedScan>> ScansFromLog(const carmen::Log& log, const std::string& source) {
  if (log.records.empty()) return Status::Error(source + ": empty log (no records)");
  std::vector<StampedScan> scans;
  for (const carmen::Laser* laser : log.Lasers()) {
    if (!scans.empty() && laser->scan.scan.size() != scans.front().scan.size()) {
      return Status::Error(source + ": laser scan " + std::to_string(scans.size() + 1) + " has " +
                           std::to_string(laser->scan.scan.size()) + " beams, the first has " +
                           std::to_string(scans.front().scan.size()) +
                           " (inconsistent beam counts)");
    }
    scans.push_back(laser->scan);
  }
  if (scans.empty()) {
    return Status::Error(source + ": no laser scans (FLASER or ROBOTLASER1 lines) in the log");
  }
  if (scans.front().scan.size() == 0) return Status::Error(source + ": laser scans have no beams");
  return scans;
}

SlamResult RunSlam(const std::vector<StampedScan>& raw_scans, const SlamOptions& options,
                   const std::function<void(std::size_t)>& progress,
                   const std::function<void(const SlamStep&)>& observe) {
  SEMCHAIN_CHECK(!raw_scans.empty());
  SlamResult result;
  std::vector<PreparedScan> prepared;
  for (const StampedScan& s : raw_scans) {
    prepared.push_back(PrepareScan(s.scan, s.LaserOffset(), options.rbpf.scan));
  }
  std::vector<StampedScan> scans = raw_scans;
  auto stage_start = std::chrono::steady_clock::now();
  auto elapsed = [&stage_start] {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - stage_start).count();
    stage_start = now;
    return seconds;
  };
  if (options.laser_odometry.enabled) {
    const std::vector<Pose2> odometry =
        ComputeLaserOdometry(raw_scans, prepared, options.laser_odometry, options.rbpf.grid,
                             options.rbpf.field, &result.laser_odometry_rejected);
    for (std::size_t i = 0; i < scans.size(); ++i) {
      scans[i].odometry = odometry[i];
      scans[i].laser_pose = odometry[i] * raw_scans[i].LaserOffset();
    }
  }
  result.laser_odometry_seconds = elapsed();
  RbpfSlam slam(options.rbpf);
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const bool processed = slam.AddScan(scans[i], static_cast<int>(i));
    if (observe) observe({i, processed, &slam, &scans});
    if (progress) progress(i + 1);
  }
  result.statistics = slam.statistics();
  result.filter_seconds = elapsed();
  std::vector<Pose2> poses =
      InterpolatedPoses(scans, scans.size(), slam.BestParticle(), &result.processed);
  result.map = *slam.BestParticle().map;
  if (options.every_scan.method == "localize") {
    auto tick = [&](std::size_t) {
      if (progress) progress(scans.size() + scans.size());
    };
    result.localized = LocalizeAll(result.map, prepared, options, &poses, tick);
    for (int pass = 0; pass < options.every_scan.refinement_passes; ++pass) {
      result.map = BuildMap(prepared, poses, options.rbpf.grid);
      result.localized = LocalizeAll(result.map, prepared, options, &poses, tick);
    }
  }
  result.map = BuildMap(prepared, poses, options.rbpf.grid);
  result.every_scan_seconds = elapsed();
  for (std::size_t i = 0; i < scans.size(); ++i) {
    result.trajectory.push_back({scans[i].scan.timestamp, poses[i]});
  }
  return result;
}

}  // namespace semchain::mapping
