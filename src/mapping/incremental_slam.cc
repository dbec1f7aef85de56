#include "mapping/incremental_slam.h"

#include <algorithm>
#include <chrono>
#include <future>
#include <utility>

#include "core/angles.h"
#include "core/check.h"
#include "core/release_memory.h"
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

// The map of the scans at 'nodes' (scan index, pose).
OccupancyGrid BuildNodeMap(const std::vector<PreparedScan>& scans,
                           const std::vector<std::pair<int, Pose2>>& nodes,
                           const OccupancyGridOptions& options) {
  OccupancyGrid map(options);
  for (const auto& [index, pose] : nodes)
    InsertScan(scans[static_cast<std::size_t>(index)], pose, &map);
  return map;
}

// Localizes every scan in 'map' from 'poses' (updated in place), searching those that fit far
// worse than their neighbours (LocalizeScans); returns how many matched, were searched, moved.
EveryScanStatistics LocalizeAll(const OccupancyGrid& map, const std::vector<PreparedScan>& scans,
                                const SlamOptions& options, std::vector<Pose2>* poses,
                                const std::function<void(std::size_t)>& tick) {
  const LikelihoodField field(map, options.rbpf.field);
  const EveryScanStatistics statistics = LocalizeScans(field, scans, poses, options.every_scan,
                                                       ResolveThreadCount(options.rbpf.threads));
  if (tick) tick(scans.size());
  return statistics;
}

// 'candidate' with the scan indices of its nodes ('node_scans', one per graph node).
LoopClosureCandidate WithScans(LoopClosureCandidate candidate, const std::vector<int>& node_scans) {
  candidate.from_scan = node_scans[static_cast<std::size_t>(candidate.from)];
  candidate.to_scan = node_scans[static_cast<std::size_t>(candidate.to)];
  return candidate;
}

std::vector<LoopClosureCandidate> WithScans(std::vector<LoopClosureCandidate> candidates,
                                            const std::vector<int>& node_scans) {
  for (LoopClosureCandidate& candidate : candidates) candidate = WithScans(candidate, node_scans);
  return candidates;
}

// 'oracle' (LoopClosureOptions::oracle or oracle_relative, may be empty) called with the scan
// indices of the candidate's nodes filled in from 'node_scans' (one per graph node; it outlives
// the result).
template <typename Verdict>
std::function<Verdict(const LoopClosureCandidate&)> WithScanIndices(
    const std::function<Verdict(const LoopClosureCandidate&)>& oracle,
    const std::vector<int>* node_scans) {
  if (!oracle) return {};
  return [oracle, node_scans](const LoopClosureCandidate& candidate) {
    return oracle(WithScans(candidate, *node_scans));
  };
}

}  // namespace

IncrementalSlam::IncrementalSlam(const SlamOptions& options)
    : options_(options),
      laser_odometry_(options.laser_odometry, options.rbpf.grid, options.rbpf.field),
      slam_(options.rbpf) {
  if (options.pose_graph && options.loop_closure.online) {
    LoopClosureOptions closer = options.loop_closure;
    closer.oracle = WithScanIndices(options.loop_closure.oracle, &node_scans_);
    closer.oracle_relative = WithScanIndices(options.loop_closure.oracle_relative, &node_scans_);
    loop_closer_.emplace(closer);
  }
}

SlamStep IncrementalSlam::AddScan(const StampedScan& raw) {
  auto start = std::chrono::steady_clock::now();
  prepared_.push_back(PrepareScan(raw.scan, raw.LaserOffset(), options_.rbpf.scan));
  StampedScan scan = raw;
  if (options_.laser_odometry.enabled) {
    scan.odometry = laser_odometry_.Add(raw, prepared_.back());
    scan.laser_pose = scan.odometry * raw.LaserOffset();
  } else if (SnapCheck()) {
    local_poses_.push_back(laser_odometry_.Add(raw, prepared_.back()));
  }
  scans_.push_back(scan);
  laser_odometry_seconds_ += SecondsSince(start);
  start = std::chrono::steady_clock::now();
  const std::size_t index = scans_.size() - 1;
  const bool processed = slam_.AddScan(scans_.back(), static_cast<int>(index));
  if (processed && loop_closer_) {
    StepGraph(static_cast<std::size_t>(options_.loop_closure.online_lag_nodes),
              options_.loop_closure.background);
  }
  filter_seconds_ += SecondsSince(start);
  return {index, processed, &slam_, &scans_, this};
}

std::vector<IncrementalSlam::GraphInput> IncrementalSlam::NewGraphNodes(std::size_t lag) const {
  // The graph takes node m once the filter is 'lag' nodes past it, from the best particle's
  // lineage then: the particle that is best at a scan is often not the one whose line survives,
  // and a few nodes of hindsight pick the line that does (on the simulated campus the nodes
  // of the best particle of the moment gave the graph a chain bent by 2 degrees).
  std::vector<GraphInput> inputs;
  const Particle& best = slam_.BestParticle();
  const auto total = static_cast<std::size_t>(slam_.statistics().processed);
  if (total <= lag) return inputs;
  const std::size_t last = total - 1 - lag;
  const std::size_t fed = loop_closer_->size();
  if (fed > last) return inputs;
  const std::size_t oldest = fed == 0 ? 0 : fed - 1;  // the node the first new one moves from
  std::vector<const TrajectoryNode*> lineage;         // nodes oldest … last, newest first
  const TrajectoryNode* node = best.trajectory.get();
  for (std::size_t k = total - 1;; --k) {
    if (k <= last) lineage.push_back(node);
    if (k == oldest) break;
    node = node->parent.get();
  }
  std::reverse(lineage.begin(), lineage.end());
  for (std::size_t j = fed == 0 ? 0 : 1; j < lineage.size(); ++j) {
    GraphInput input;
    input.scan_index = lineage[j]->scan_index;
    input.scan = prepared_[static_cast<std::size_t>(input.scan_index)];
    input.first = fed == 0 && j == 0;
    input.pose = input.first ? lineage[j]->pose : lineage[j - 1]->pose.Between(lineage[j]->pose);
    input.local = LocalPose(input.scan_index);
    inputs.push_back(std::move(input));
  }
  return inputs;
}

bool IncrementalSlam::FeedGraph(const std::vector<GraphInput>& inputs, LoopCloser* closer,
                                const LoopClosureOptions& options) {
  bool optimized = false;
  for (const GraphInput& input : inputs) {
    const Pose2 pose = input.first ? input.pose : closer->filter_poses().back() * input.pose;
    optimized |= closer->AddNode(input.scan, pose, input.local);
  }
  if (!optimized) return false;
  const std::vector<Pose2>& estimate = closer->estimate();
  const std::vector<Pose2>& given = closer->filter_poses();
  for (std::size_t j = 0; j < estimate.size(); ++j) {
    if ((estimate[j].translation() - given[j].translation()).norm() >
            options.follow_min_shift_meters ||
        std::abs(NormalizeAngle(estimate[j].theta - given[j].theta)) >
            options.follow_min_turn_radians) {
      return true;
    }
  }
  return false;
}

void IncrementalSlam::WaitForGraph() const {
  if (!graph_job_.valid()) return;
  follow_pending_ = graph_job_.get() || follow_pending_;
}

std::vector<IncrementalSlam::GraphInput> IncrementalSlam::TakeGraphNodes(std::size_t lag) const {
  std::vector<GraphInput> inputs = NewGraphNodes(lag);
  for (const GraphInput& input : inputs) node_scans_.push_back(input.scan_index);
  return inputs;
}

bool IncrementalSlam::SnapCheck() const {
  return options_.pose_graph && options_.loop_closure.snap_sigmas > 0.0;
}

std::optional<Pose2> IncrementalSlam::LocalPose(int scan_index) const {
  if (!SnapCheck()) return std::nullopt;
  const auto i = static_cast<std::size_t>(scan_index);
  return options_.laser_odometry.enabled ? scans_[i].odometry : local_poses_[i];
}

void IncrementalSlam::FollowIfPending() {
  if (follow_pending_) FollowPoseGraph();
  follow_pending_ = false;
}

void IncrementalSlam::StepGraph(std::size_t lag, bool background) {
  WaitForGraph();
  FollowIfPending();
  std::vector<GraphInput> inputs = TakeGraphNodes(lag);
  if (inputs.empty()) return;
  LoopCloser* closer = &*loop_closer_;
  const LoopClosureOptions* options = &options_.loop_closure;
  if (!background) {
    follow_pending_ = FeedGraph(inputs, closer, *options);
    FollowIfPending();
    return;
  }
  // The graph works on these nodes while the filter takes the next scans; the next processed
  // scan waits for it (so the results do not depend on how fast either side is) and the
  // particles follow then.
  graph_job_ = std::async(std::launch::async, [inputs = std::move(inputs), closer, options] {
    return FeedGraph(inputs, closer, *options);
  });
}

void IncrementalSlam::FollowPoseGraph() {
  // The nodes in the graph at their optimized poses; each particle keeps its own newer nodes,
  // moved by the correction that puts the best particle's line on the graph's newest node.
  const std::vector<Pose2>& estimate = loop_closer_->estimate();
  const auto recent =
      static_cast<int>(slam_.statistics().processed) - static_cast<int>(estimate.size()) + 1;
  std::vector<const TrajectoryNode*> newer;  // the best particle's nodes after the graph's
  const TrajectoryNode* newest_in_graph = slam_.BestParticle().trajectory.get();
  for (int k = 0; k + 1 < recent; ++k) {
    newer.push_back(newest_in_graph);
    newest_in_graph = newest_in_graph->parent.get();
  }
  SEMCHAIN_CHECK(newest_in_graph->scan_index == node_scans_.back());
  const Pose2 correction = estimate.back() * newest_in_graph->pose.Inverse();
  auto map = std::make_shared<OccupancyGrid>(options_.rbpf.grid);
  std::shared_ptr<const TrajectoryNode> history;
  for (std::size_t j = 0; j < estimate.size(); ++j) {
    const int scan = node_scans_[j];
    InsertScan(prepared_[static_cast<std::size_t>(scan)], estimate[j], map.get());
    if (j + 1 < estimate.size()) {
      history = std::make_shared<const TrajectoryNode>(TrajectoryNode{estimate[j], scan, history});
    }
  }
  for (const TrajectoryNode* node : newer) {
    InsertScan(prepared_[static_cast<std::size_t>(node->scan_index)], correction * node->pose,
               map.get());
  }
  slam_.Follow(correction, map, history, recent);
  loop_closer_->Rebase();
  ++follows_;
}

std::vector<std::pair<int, Pose2>> IncrementalSlam::Nodes(std::vector<int>* processed) const {
  std::vector<std::pair<int, Pose2>> nodes = BestNodes(slam_.BestParticle(), processed);
  if (!loop_closer_ || loop_closer_->size() == 0) return nodes;
  // The best particle's line, moved node by node by what the graph did to the node it was given
  // (estimate · given⁻¹), the newer nodes by the newest correction: the graph's loop closures
  // on the line that the filter's hindsight picked (before the particles last followed the
  // graph, the line and the graph's input are the same poses).
  const std::vector<Pose2>& estimate = loop_closer_->estimate();
  const std::vector<Pose2>& given = loop_closer_->filter_poses();
  Pose2 correction;
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    if (j < estimate.size()) {
      SEMCHAIN_CHECK(nodes[j].first == node_scans_[j]);
      correction = estimate[j] * given[j].Inverse();
    }
    nodes[j].second = correction * nodes[j].second;
  }
  return nodes;
}

std::vector<StampedPose> IncrementalSlam::Trajectory() const {
  SEMCHAIN_CHECK(!scans_.empty());
  WaitForGraph();
  std::vector<int> processed;
  const std::vector<Pose2> poses = InterpolatedPoses(scans_, scans_.size(), Nodes(&processed));
  std::vector<StampedPose> trajectory;
  trajectory.reserve(scans_.size());
  for (std::size_t i = 0; i < scans_.size(); ++i) {
    trajectory.push_back({scans_[i].scan.timestamp, poses[i]});
  }
  return trajectory;
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
  if (loop_closer_) {
    // The last nodes, not yet past the lag (the particles no longer follow).
    WaitForGraph();
    follow_pending_ = false;
    FeedGraph(TakeGraphNodes(0), &*loop_closer_, options_.loop_closure);
    std::vector<int> scans;
    std::vector<Pose2> line;
    for (const auto& node : BestNodes(slam_.BestParticle(), &scans)) line.push_back(node.second);
    loop_closer_->Reoptimize(line);
  }
  std::vector<std::pair<int, Pose2>> nodes = Nodes(&result.processed);
  // The filter's map (a copy shares its cells), unless the pose graph moves the nodes: then the
  // map of the optimized trajectory is built below. The filter is not needed after this.
  OccupancyGrid filter_map;
  if (!options_.pose_graph) filter_map = *slam_.BestParticle().map;
  if (release_filter) {
    release_filter();
    ReleaseFreeMemory();
  }
  if (loop_closer_) {
    result.loop_closure = loop_closer_->statistics();
    result.loop_closure.follows = follows_;
    result.loop_closure_candidates = WithScans(loop_closer_->candidates(), node_scans_);
  } else if (options_.pose_graph) {
    std::vector<const PreparedScan*> node_scans;
    std::vector<Pose2> node_poses;
    std::vector<Pose2> local_poses;
    for (const auto& [index, pose] : nodes) {
      node_scans.push_back(&prepared_[static_cast<std::size_t>(index)]);
      node_poses.push_back(pose);
      if (const std::optional<Pose2> local = LocalPose(index)) local_poses.push_back(*local);
    }
    std::vector<int> node_indices;
    for (const auto& node : nodes) node_indices.push_back(node.first);
    LoopClosureOptions closer = options_.loop_closure;
    closer.oracle = WithScanIndices(options_.loop_closure.oracle, &node_indices);
    closer.oracle_relative = WithScanIndices(options_.loop_closure.oracle_relative, &node_indices);
    LoopClosureResult closed = CloseLoops(node_scans, node_poses, local_poses, closer);
    for (std::size_t k = 0; k < nodes.size(); ++k) nodes[k].second = closed.poses[k];
    result.loop_closure = std::move(closed.statistics);
    result.loop_closure_candidates = WithScans(std::move(closed.candidates), node_indices);
    ReleaseFreeMemory();  // the graph's submaps, before the final map is built
  }
  std::vector<Pose2> poses = InterpolatedPoses(scans_, scans_.size(), nodes);
  // With the pose graph, the map the scans are localized in is made of the same scans as the
  // filter's, at their optimized poses: the scans in between, at interpolated poses, would
  // blur it (Intel: relation error 0.0155 m instead of 0.0138 m).
  result.map = options_.pose_graph ? BuildNodeMap(prepared_, nodes, options_.rbpf.grid)
                                   : std::move(filter_map);
  if (options_.every_scan.method == "localize") {
    auto tick = [&](std::size_t) {
      if (progress) progress(scans_.size() + scans_.size());
    };
    result.every_scan = LocalizeAll(result.map, prepared_, options_, &poses, tick);
    for (int pass = 0; pass < options_.every_scan.refinement_passes; ++pass) {
      result.map = BuildMap(prepared_, poses, options_.rbpf.grid);
      result.every_scan = LocalizeAll(result.map, prepared_, options_, &poses, tick);
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
