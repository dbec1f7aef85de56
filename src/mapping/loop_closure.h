#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "core/pose2.h"
#include "mapping/loop_closure_options.h"
#include "mapping/prepared_scan.h"

// The pose graph behind the particle filter (DESIGN.md §3.2): the best particle's trajectory
// becomes graph nodes, consecutive nodes are tied by the motion the filter found (loosened where
// it snapped onto older map, LoopClosureOptions::snap_sigmas), nodes are
// grouped into submaps (rigid local maps, Cartographer's idea), and every few nodes the scan is
// searched for in the older submaps with the branch-and-bound matcher, in a window as wide as
// the drift the motion since the submap (or the last closure) allows. A match above the score
// that the motion also allows becomes a loop-closure edge (one it does not allow waits for a
// second that agrees); sparse pose adjustment with a robust loss then moves the nodes, and a
// closure the others contradict is dropped.
namespace semchain::mapping {

struct LoopClosureStatistics {
  int nodes = 0;
  int submaps = 0;
  int searches = 0;  // nodes searched from
  int found = 0;     // matches above the score
  int accepted = 0;  // closures kept
  int rejected = 0;  // closures dropped as inconsistent with the other closures
  int gated = 0;     // closures not added: inconsistent with the motion since (gate_sigmas)
  int loosened = 0;  // motion edges loosened where the filter snapped (snap_sigmas)
  int optimizations = 0;
  int follows = 0;  // online: times the particles and their map moved onto the optimized nodes
  double motion_noise_scale = 1.0;  // the motion edges' variance factor at the end
  double search_seconds = 0.0;
  double built_submaps_peak_megabytes = 0.0;  // the most the built submaps held at once
  double optimizer_seconds = 0.0;
  // Whitened residual norm of each kept closure after the last optimization.
  std::vector<double> residuals;
};

// What became of a match the loop closer scored (LoopClosureOptions::record_candidates).
enum class ClosureVerification {
  kNotReached,  // not the search's closure: another submap scored higher, or below min_score
  kAdded,       // added to the graph when found
  kConfirmed,   // held back (off the motion's prediction, or every closure waits), then added
                // when a later closure agreed with it
  kHeldBack,    // held back and never confirmed
};

struct LoopClosureCandidate {
  int from = 0;  // first node of the submap matched (the closure's 'from')
  int to = 0;    // the node searched from
  int submap = 0;
  // Scan indices of the two nodes, where the caller knows them (IncrementalSlam); else -1.
  int from_scan = -1;
  int to_scan = -1;
  double score = 0.0;           // branch-and-bound score (mean M of the query's points, 0..1)
  Pose2 relative;               // node 'to' in the frame of node 'from', refined as a closure is
  bool best_of_search = false;  // the highest score of the submaps searched from 'to'
  // The score gate: best of its search, at least min_score and, with unknown_is_neutral, enough
  // of the query on observed cells scoring min_score there. Only these reach verification.
  bool passed_score = false;
  ClosureVerification verification = ClosureVerification::kNotReached;
  // Mahalanobis distance (σ) of the closure from where the graph predicted the node when found
  // (what gate_sigmas compares; 0 for candidates that did not reach verification).
  double innovation_sigmas = 0.0;
  // At the end: still an edge of the graph (not dropped by the back end), its whitened
  // residual norm and the weight the loop-closure loss gives it (LoopEdgeWeight; 0 when not in
  // the graph).
  bool in_graph = false;
  double residual_sigmas = 0.0;
  double weight = 0.0;
};

struct LoopClosureResult {
  std::vector<Pose2> poses;  // one per node, optimized
  LoopClosureStatistics statistics;
  std::vector<LoopClosureCandidate> candidates;  // with record_candidates
};

// The pose graph fed one node at a time, while the filter runs: AddNode takes node i's scan and
// the filter's pose for it, adds the motion edge from node i − 1 and the scan to the open submap,
// and every search_every_nodes nodes searches the finished submaps for a loop closure and, when
// one is added, optimizes. When the filter follows the optimized poses (its particles and map
// moved onto them), Rebase() makes the estimate the filter's poses from then on, so that the
// next motion edges are measured in the frame the filter now works in.
class LoopCloser {
 public:
  // 'options' must be valid.
  explicit LoopCloser(const LoopClosureOptions& options);
  ~LoopCloser();
  LoopCloser(LoopCloser&&) noexcept;
  LoopCloser& operator=(LoopCloser&&) noexcept;

  // Adds the next node (its scan goes into the open submap, and its match points are kept for
  // the searches); returns true when the graph was optimized. 'local_pose' (optional) is a local
  // estimate of the node's pose, in a frame of its own (the laser odometry's): where the filter's
  // step from the previous node disagrees with its step, the motion edge is loosened
  // (LoopClosureOptions::snap_sigmas).
  bool AddNode(const PreparedScan& scan, const Pose2& filter_pose,
               const std::optional<Pose2>& local_pose = std::nullopt);
  std::size_t size() const;
  // The graph's poses, one per node.
  const std::vector<Pose2>& estimate() const;
  // The filter's poses, one per node, as given (the estimate's up to the last Rebase).
  const std::vector<Pose2>& filter_poses() const;
  void Rebase();
  // Replaces the filter's poses by 'filter_poses' (one per node; the line the filter finally
  // kept, which hindsight makes better than what it gave node by node), re-derives the motion
  // edges from them and optimizes again with the loop closures found (no new search).
  void Reoptimize(const std::vector<Pose2>& filter_poses);
  LoopClosureStatistics statistics() const;
  // With record_candidates: every match scored, in the order found, with its state now.
  std::vector<LoopClosureCandidate> candidates() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// Runs the pose graph over the nodes in order, as it would run while they arrive: 'scans' and
// 'poses' (the filter's, one per node) of the same length, and 'local_poses' the same length or
// empty (LoopCloser::AddNode). 'progress' (may be empty) is called with the nodes done.
LoopClosureResult CloseLoops(const std::vector<const PreparedScan*>& scans,
                             const std::vector<Pose2>& poses, const std::vector<Pose2>& local_poses,
                             const LoopClosureOptions& options,
                             const std::function<void(std::size_t)>& progress = {});

// The same without local estimates.
LoopClosureResult CloseLoops(const std::vector<const PreparedScan*>& scans,
                             const std::vector<Pose2>& poses, const LoopClosureOptions& options,
                             const std::function<void(std::size_t)>& progress = {});

}  // namespace semchain::mapping
