#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <future>
#include <optional>
#include <vector>

#include "io/trajectory_io.h"
#include "mapping/laser_odometry.h"
#include "mapping/loop_closure.h"
#include "mapping/prepared_scan.h"
#include "mapping/rbpf_slam.h"
#include "mapping/slam_options.h"

// `semchain slam`'s SLAM fed one scan at a time (the ROS node's mapping mode; RunSlam feeds it a
// whole log): each scan goes through the laser-odometry front end and then the RBPF, so that
// the map and the best trajectory are known after every scan. Finish() runs the final passes
// (a pose for every scan in the final map) as RunSlam does.
namespace semchain::mapping {

class IncrementalSlam;

// What a caller sees of the filter after each scan, while SLAM runs (live semantic mapping).
struct SlamStep {
  std::size_t scan = 0;    // index of the scan just added
  bool processed = false;  // the filter updated on it (the best particle may have changed)
  const RbpfSlam* slam = nullptr;
  const std::vector<StampedScan>* scans = nullptr;  // the odometry the filter uses
  const IncrementalSlam* source = nullptr;          // its Trajectory() is the one so far
};

struct SlamResult {
  OccupancyGrid map;                    // built from the final poses
  std::vector<StampedPose> trajectory;  // one pose per scan, in log order
  std::vector<int> processed;           // indices of the scans the RBPF processed
  EveryScanStatistics every_scan;       // scans localized (and searched) in the final map
  int laser_odometry_rejected = 0;      // scans that kept their wheel odometry increment
  RbpfStatistics statistics;
  LoopClosureStatistics loop_closure;  // with SlamOptions::pose_graph
  // With the pose graph's record_candidates: every match its searches scored, with the scan
  // indices of their nodes.
  std::vector<LoopClosureCandidate> loop_closure_candidates;
  // Wall time of each stage, seconds.
  double laser_odometry_seconds = 0.0;
  double filter_seconds = 0.0;
  double every_scan_seconds = 0.0;
};

class IncrementalSlam {
 public:
  // 'options' must be valid (SlamOptions::Validate).
  explicit IncrementalSlam(const SlamOptions& options);
  IncrementalSlam(const IncrementalSlam&) = delete;
  IncrementalSlam& operator=(const IncrementalSlam&) = delete;

  // Adds the next scan (its timestamp not before the last one's; any beam geometry).
  // The step refers to this object and is valid until the next call.
  SlamStep AddScan(const StampedScan& scan);

  std::size_t size() const { return scans_.size(); }
  // The scans with the odometry the filter uses (the laser odometry's when enabled).
  const std::vector<StampedScan>& scans() const { return scans_; }
  const RbpfSlam& filter() const { return slam_; }
  // The trajectory so far (one pose per scan; at least one scan added): the best particle's,
  // or with the online pose graph the graph's optimized nodes, odometry in between.
  std::vector<StampedPose> Trajectory() const;

  // The final passes on the scans added (at least one): 'progress' (may be empty) is called
  // with scans done counting on from size(), as RunSlam reports them. On an object about to go
  // (std::move(slam).Finish()) the particles are dropped as soon as the best one's trajectory
  // and map are taken, so that the other particles' maps never share memory with the pose
  // graph's search or the final map; the results are the same.
  SlamResult Finish(const std::function<void(std::size_t)>& progress = {}) const&;
  SlamResult Finish(const std::function<void(std::size_t)>& progress = {}) &&;

 private:
  // Finish's passes; 'release_filter' (may be empty) runs once the filter is no longer needed.
  SlamResult FinalPasses(const std::function<void(std::size_t)>& progress,
                         const std::function<void()>& release_filter) const;
  // The online pose graph. A node for it: the scan, and the best particle's motion to it from
  // the previous node (or its pose, for the first node).
  struct GraphInput {
    int scan_index = 0;
    PreparedScan scan;
    Pose2 pose;
    bool first = false;
    std::optional<Pose2> local;  // the scan's local pose, with the snap check
  };
  // The nodes the graph may take now: those the filter is 'lag' nodes past, not yet in it.
  std::vector<GraphInput> NewGraphNodes(std::size_t lag) const;
  // NewGraphNodes, their scan indices recorded as the graph's next nodes.
  std::vector<GraphInput> TakeGraphNodes(std::size_t lag) const;
  // Adds them to 'closer'; true when an optimization moved some node far enough from the
  // filter's line for the particles to follow (runs on the graph's thread in the background).
  static bool FeedGraph(const std::vector<GraphInput>& inputs, LoopCloser* closer,
                        const LoopClosureOptions& options);
  // At a processed scan: waits for the graph's last work, makes the particles follow it if it
  // asked for that, and hands the graph its new nodes (in the background, or here).
  void StepGraph(std::size_t lag, bool background);
  // Waits for the graph's work in flight and keeps whether the particles should follow (they do
  // at the next processed scan, whoever waited). Const: Trajectory() and Finish() wait too.
  void WaitForGraph() const;
  void FollowPoseGraph();
  void FollowIfPending();  // FollowPoseGraph when the graph asked for it
  // Whether the pose graph checks the filter's steps against the laser odometry's.
  bool SnapCheck() const;
  // With SnapCheck(), the laser-odometry pose of scan 'scan_index' (the filter's own odometry
  // when it runs on the laser odometry); otherwise none.
  std::optional<Pose2> LocalPose(int scan_index) const;
  // The processed scans' indices and poses the final trajectory is interpolated between.
  std::vector<std::pair<int, Pose2>> Nodes(std::vector<int>* processed) const;

  SlamOptions options_;
  LaserOdometry laser_odometry_;
  RbpfSlam slam_;
  std::vector<PreparedScan> prepared_;
  std::vector<StampedScan> scans_;
  // With the pose graph's snap check (LoopClosureOptions::snap_sigmas) and a filter on wheel
  // odometry, each scan's laser-odometry pose, computed beside the filter (LocalPose).
  std::vector<Pose2> local_poses_;
  // With the online pose graph: the graph and the scan index of each of its nodes.
  mutable std::optional<LoopCloser> loop_closer_;
  mutable std::vector<int> node_scans_;
  mutable std::future<bool> graph_job_;  // the graph's work in flight (background)
  mutable bool follow_pending_ = false;
  int follows_ = 0;
  double laser_odometry_seconds_ = 0.0;
  double filter_seconds_ = 0.0;
};

}  // namespace semchain::mapping
