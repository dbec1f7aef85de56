#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "mapping/branch_and_bound_matcher.h"
#include "mapping/ceres_scan_matcher.h"
#include "mapping/match_grid.h"
#include "mapping/occupancy_grid.h"
#include "mapping/pose_graph.h"
#include "mapping/prepared_scan.h"

// The pose graph behind the particle filter (DESIGN.md §3.2): the best particle's trajectory
// becomes graph nodes, consecutive nodes are tied by the motion the filter found, nodes are
// grouped into submaps (rigid local maps, Cartographer's idea), and every few nodes the scan is
// searched for in the older submaps with the branch-and-bound matcher, in a window as wide as
// the drift the motion since the submap (or the last closure) allows. A match above the score
// that the motion also allows becomes a loop-closure edge (one it does not allow waits for a
// second that agrees); sparse pose adjustment with a robust loss then moves the nodes, and a
// closure the others contradict is dropped.
namespace semchain::mapping {

struct LoopClosureOptions {
  // Nodes of this much travel form one submap.
  double submap_travel_meters = 15.0;
  OccupancyGridOptions submap_grid;
  MatchGridOptions match_grid;
  BranchAndBoundOptions matcher{6, 0.0};
  // Finished submaps whose match grid and precomputed matcher are kept built (the ones searched
  // most recently); the others keep only their occupancy grid and are rebuilt, identically, when
  // a search reaches them again. Bounds the memory of long runs (a campus: ~100 submaps).
  int max_built_submaps = 12;
  // ...and at most this much memory in them (match grid and precomputation grids; the least
  // recently searched are freed first, the two in use never). A submap's grids grow with what
  // its laser saw: twelve of MIT Killian's (corridors) hold 76 MB, twelve of ACES's (open
  // halls) 148 MB. A cap that frees submaps a search keeps coming back to costs time: ACES with
  // 64 MB, 341 MB peak RSS instead of 425 MB, but the search took 11.2 s instead of 5.3 s
  // (docs/results.md, "Campus logs with synthetic odometry"). 128 MB bounds larger submaps without
  // slowing these logs.
  double max_built_submaps_megabytes = 128.0;
  // A submap is searched only from nodes at least this far along the path after its last
  // node (nearer ones are the filter's own business).
  double min_loop_travel_meters = 30.0;
  // Searches run from every n-th node.
  int search_every_nodes = 3;
  // Search window: ±window_sigmas standard deviations of the node's pose relative to the
  // submap (ChainUncertainty over the motion edges since the submap or the last accepted
  // closure, whichever is later), at least the floors below and at most the caps. A window no
  // wider than the drift the motion allows keeps a look-alike place one room away out of reach.
  double window_sigmas = 3.0;
  double linear_window_meters = 1.0;
  double max_linear_window_meters = 10.0;
  double angular_window_radians = 0.15;
  double max_angular_window_radians = 0.6;
  // A found closure further than this many standard deviations (Mahalanobis, the chain's
  // uncertainty plus the closure's own) from where the graph puts the node is inconsistent with
  // the motion since and is held back (0: no gate).
  double gate_sigmas = 3.0;
  // A held-back closure is added after all when a later closure, found within
  // confirm_within_meters of travel but at least confirm_min_separation_meters after it, agrees
  // with it (the motion between their nodes within gate_sigmas): drift larger than the motion
  // model allows then still gets corrected, a lone aliased match does not.
  double confirm_within_meters = 10.0;
  double confirm_min_separation_meters = 0.0;
  // The confirmation rules made for corridors (config/slam-campus.yaml): every closure held back
  // within confirm_within_meters may be confirmed (not only the last one), one held back for
  // being off the prediction only by a closure to another submap (a corridor's aliased shift can
  // fit one submap's stretch twice, rarely two submaps' alike), and two closures to different
  // submaps agree within the chain's uncertainty between those submaps too. Off by default:
  // made on the simulated campus, they were first applied to every configuration, and the
  // default pose graph then gave FR campus 9.90 m instead of 1.17 m and Killian 4.39 m instead
  // of 2.43 m (docs/results.md, "Campus logs with synthetic odometry").
  bool corridor_confirmation = false;
  // Every closure, not only one off the prediction, waits for such a confirmation (or agrees
  // with the last accepted closure, found within confirm_within_meters). On a long loop the
  // motion model admits a window of metres, and down a corridor an aliased shift along it can
  // lie within the prediction. Off by default, like query_travel_meters and unknown_is_neutral:
  // together they fix the simulated campus (config/slam-campus.yaml) but move the synthetic
  // drift case of loop_closure_test (a constant heading drift) from 0.29 to 0.41 m.
  bool confirm_every_closure = false;
  // A match must score at least this (mean M of its points, 0..1) and have this many points.
  double min_score = 0.65;
  int min_points = 40;
  // A search's best match scoring at least this but under min_score is held back like a closure
  // off the prediction: added only when a later closure agrees with it (or it agrees with the
  // last closure accepted), as a revisit of open space with few features scores low but its
  // neighbours agree with it, and an aliased match rarely has one that does. 0: off (such
  // matches are dropped).
  double consistent_min_score = 0.0;
  // Returns on cells the submap never observed count as just under min_score in the search
  // (neither for nor against, and never enough for a pose with all its returns there), and an
  // accepted match needs min_known_fraction of its returns on observed cells scoring min_score
  // there. Otherwise (false) they count as misses, and the search prefers any pose that puts more
  // of the query on the submap: entering a corridor's submap from behind, a shift of metres along
  // it.
  bool unknown_is_neutral = false;
  double min_known_fraction = 0.3;
  double match_max_range_meters = 20.0;
  int match_beam_step = 2;
  // The query matched against a submap: node i's scan and the scans of the nodes within this
  // much travel before it (0: the scan alone), thinned to one point per query_cell_meters cell.
  double query_travel_meters = 0.0;
  double query_cell_meters = 0.1;
  // The branch-and-bound pose (on the cell and angle grid) refined on the submap, as
  // Cartographer refines its loop closures.
  CeresScanMatcherOptions refinement;
  // Uncertainties of the edges: consecutive nodes (standard deviations growing with the motion)
  // and loop closures; they also size the search window and the gate above.
  double odometry_sigma_meters = 0.02;
  double odometry_sigma_per_meter = 0.02;
  double odometry_sigma_radians = 0.005;
  double odometry_sigma_radians_per_radian = 0.02;
  double loop_sigma_meters = 0.05;
  double loop_sigma_radians = 0.01;
  // In the optimization the motion edges' variances are multiplied by the smallest factor under
  // which every accepted closure's innovation (how far it landed from where the graph predicted
  // it) lies in its 99 % region, within these bounds: a filter better than the model above is
  // then not bent by its closures' match noise, one that drifts more gets the slack to be
  // corrected. The search window and the gate keep the model as it is (a factor that shrank
  // there would hide the closures that should raise it).
  bool adapt_motion_noise = true;
  double min_motion_noise_scale = 1e-4;
  double max_motion_noise_scale = 1.0;
  // A closure whose whitened residual after optimization exceeds this is contradicted by the
  // others and dropped.
  double max_residual_sigmas = 5.0;
  PoseGraphOptions optimizer;
  // How the graph runs beside the filter (IncrementalSlam). Online: the best particle's pose goes
  // in as a node at every scan the filter processes, and once an optimization has moved some node
  // more than follow_min_shift_meters or follow_min_turn_radians from where the filter put it,
  // the particles follow: their map is rebuilt from the optimized nodes and every particle is
  // moved by the correction that puts the best one on its optimized node, so that the filter
  // maps on from the closed loop instead of mapping a corridor twice. Otherwise the graph runs
  // once over the final best particle's nodes, after the filter.
  bool online = false;
  // Online, node m goes in once the filter has processed this many nodes after it, from the
  // best particle's line then (a short hindsight: the best particle of the moment is often not
  // the one whose line survives).
  int online_lag_nodes = 10;
  // Online, the graph searches and optimizes on a thread of its own while the filter takes the
  // next scans; the filter waits for it at the next processed scan (the results do not depend on
  // timing), so the particles follow one node later than with false (all on the filter's thread).
  // Off by default: on the simulated campus the search is a tenth of the run and the wall time
  // did not change (docs/experiments.md, "Pose graph").
  bool background = false;
  double follow_min_shift_meters = 0.1;
  double follow_min_turn_radians = 0.02;
  // Measurement (`semchain bench closures`): every submap searched keeps its best match scoring
  // at least record_min_score as a candidate (LoopCloser::candidates()), refined as a closure
  // is. Each submap is then searched down to that score instead of the best score found so far,
  // which is slower, but the search picks the same closures (branch-and-bound finds the same
  // best pose above any lower bound), so the result does not change.
  bool record_candidates = false;
  double record_min_score = 0.4;

  bool Validate(std::string* error) const;
};

struct LoopClosureStatistics {
  int nodes = 0;
  int submaps = 0;
  int searches = 0;  // nodes searched from
  int found = 0;     // matches above the score
  int accepted = 0;  // closures kept
  int rejected = 0;  // closures dropped as inconsistent with the other closures
  int gated = 0;     // closures not added: inconsistent with the motion since (gate_sigmas)
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
  // the searches); returns true when the graph was optimized.
  bool AddNode(const PreparedScan& scan, const Pose2& filter_pose);
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
// 'poses' (the filter's, one per node) of the same length. 'progress' (may be empty) is called
// with the nodes done.
LoopClosureResult CloseLoops(const std::vector<const PreparedScan*>& scans,
                             const std::vector<Pose2>& poses, const LoopClosureOptions& options,
                             const std::function<void(std::size_t)>& progress = {});

}  // namespace semchain::mapping
