#include "mapping/incremental_slam.h"

#include <atomic>
#include <chrono>
#include <utility>

#include "core/check.h"
#include "mapping/parallel_for.h"
#include "mapping/ray_casting.h"

namespace semchain::mapping {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The pose of each of the first 'count' scans from the poses of the scans the filter
// processed (interpolated odometry in between).
std::vector<Pose2> InterpolatedPoses(const std::vector<StampedScan>& scans, std::size_t count,
                                     const std::vector<std::pair<int, Pose2>>& corrected) {
  std::vector<Pose2> odometry;
  std::vector<double> timestamps;
  for (std::size_t i = 0; i < count; ++i) {
    odometry.push_back(scans[i].odometry);
    timestamps.push_back(scans[i].scan.timestamp);
  }
  return InterpolateTrajectory(odometry, timestamps, corrected);
}

// The best particle's poses at the scans it processed, and their indices.
std::vector<std::pair<int, Pose2>> BestNodes(const Particle& best, std::vector<int>* processed) {
  std::vector<std::pair<int, Pose2>> nodes;
  for (const TrajectoryNode* node : Unroll(best.trajectory)) {
    nodes.emplace_back(node->scan_index, node->pose);
    processed->push_back(node->scan_index);
  }
  return nodes;
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
  const std::vector<Pose2> poses =
      InterpolatedPoses(scans, count, BestNodes(slam.BestParticle(), &processed));
  std::vector<StampedPose> trajectory;
  trajectory.reserve(count);
  for (std::size_t i = 0; i < count; ++i) trajectory.push_back({scans[i].scan.timestamp, poses[i]});
  return trajectory;
}

IncrementalSlam::IncrementalSlam(const SlamOptions& options)
    : options_(options),
      laser_odometry_(options.laser_odometry, options.rbpf.grid, options.rbpf.field),
      slam_(options.rbpf) {}

SlamStep IncrementalSlam::AddScan(const StampedScan& raw) {
  auto start = std::chrono::steady_clock::now();
  prepared_.push_back(PrepareScan(raw.scan, raw.LaserOffset(), options_.rbpf.scan));
  StampedScan scan = raw;
  if (options_.laser_odometry.enabled) {
    scan.odometry = laser_odometry_.Add(raw, prepared_.back());
    scan.laser_pose = scan.odometry * raw.LaserOffset();
  }
  scans_.push_back(scan);
  laser_odometry_seconds_ += SecondsSince(start);
  start = std::chrono::steady_clock::now();
  const std::size_t index = scans_.size() - 1;
  const bool processed = slam_.AddScan(scans_.back(), static_cast<int>(index));
  filter_seconds_ += SecondsSince(start);
  return {index, processed, &slam_, &scans_};
}

std::vector<StampedPose> IncrementalSlam::Trajectory() const {
  return CurrentTrajectory(scans_, scans_.size(), slam_);
}

SlamResult IncrementalSlam::Finish(const std::function<void(std::size_t)>& progress) const& {
  return FinalPasses(progress, {});
}

SlamResult IncrementalSlam::Finish(const std::function<void(std::size_t)>& progress) && {
  return FinalPasses(progress, [this] { slam_.DropParticles(); });
}

SlamResult IncrementalSlam::FinalPasses(const std::function<void(std::size_t)>& progress,
                                        const std::function<void()>& release_filter) const {
  SEMCHAIN_CHECK(!scans_.empty());
  const auto start = std::chrono::steady_clock::now();
  SlamResult result;
  result.laser_odometry_rejected = laser_odometry_.rejected();
  result.laser_odometry_seconds = laser_odometry_seconds_;
  result.filter_seconds = filter_seconds_;
  result.statistics = slam_.statistics();
  std::vector<std::pair<int, Pose2>> nodes = BestNodes(slam_.BestParticle(), &result.processed);
  // The filter's map (a copy shares its cells), unless the pose graph moves the nodes: then the
  // map of the optimized trajectory is built below. The filter is not needed after this.
  OccupancyGrid filter_map;
  if (!options_.pose_graph) filter_map = *slam_.BestParticle().map;
  if (release_filter) release_filter();
  if (options_.pose_graph) {
    std::vector<const PreparedScan*> node_scans;
    std::vector<Pose2> node_poses;
    for (const auto& [index, pose] : nodes) {
      node_scans.push_back(&prepared_[static_cast<std::size_t>(index)]);
      node_poses.push_back(pose);
    }
    LoopClosureResult closed = CloseLoops(node_scans, node_poses, options_.loop_closure);
    for (std::size_t k = 0; k < nodes.size(); ++k) nodes[k].second = closed.poses[k];
    result.loop_closure = std::move(closed.statistics);
  }
  std::vector<Pose2> poses = InterpolatedPoses(scans_, scans_.size(), nodes);
  result.map =
      options_.pose_graph ? BuildMap(prepared_, poses, options_.rbpf.grid) : std::move(filter_map);
  if (options_.every_scan.method == "localize") {
    auto tick = [&](std::size_t) {
      if (progress) progress(scans_.size() + scans_.size());
    };
    result.localized = LocalizeAll(result.map, prepared_, options_, &poses, tick);
    for (int pass = 0; pass < options_.every_scan.refinement_passes; ++pass) {
      result.map = BuildMap(prepared_, poses, options_.rbpf.grid);
      result.localized = LocalizeAll(result.map, prepared_, options_, &poses, tick);
    }
  }
  // Released first: once the filter is gone this map is the last holder of its cells.
  result.map = OccupancyGrid();
  result.map = BuildMap(prepared_, poses, options_.rbpf.grid);
  result.every_scan_seconds = SecondsSince(start);
  for (std::size_t i = 0; i < scans_.size(); ++i) {
    result.trajectory.push_back({scans_[i].scan.timestamp, poses[i]});
  }
  return result;
}

}  // namespace semchain::mapping
