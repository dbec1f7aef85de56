#pragma once

#include <functional>
#include <optional>
#include <string>

#include "mapping/branch_and_bound_matcher.h"
#include "mapping/ceres_scan_matcher.h"
#include "mapping/match_covariance.h"
#include "mapping/match_grid.h"
#include "mapping/occupancy_grid.h"
#include "mapping/pose_graph.h"

// The pose graph's options (loop_closure.h includes them), apart from the loop closer: their
// documented knobs are most of what the closer's header held, and a file that only holds or
// checks them (SLAM options, their YAML keys) need not see the closer's own types.
namespace semchain::mapping {

struct LoopClosureCandidate;  // loop_closure.h

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
  // A closure's covariance from its match's score around it (match_covariance.h, as Karto's),
  // plus the loop sigmas below, instead of those sigmas alone: a match down a corridor then
  // says where across the corridor the node is, not where along it, and an alias several
  // doors away along it no longer bends the graph (the simulated campus seed 1, aligned ATE:
  // 1.87 m without, 0.15 m with; docs/results.md, "The pose graph by default").
  bool match_covariance = true;
  MatchCovarianceOptions covariance;
  // Uncertainties of the edges: consecutive nodes (standard deviations growing with the motion)
  // and loop closures; they also size the search window and the gate above.
  double odometry_sigma_meters = 0.02;
  double odometry_sigma_per_meter = 0.02;
  double odometry_sigma_radians = 0.005;
  double odometry_sigma_radians_per_radian = 0.02;
  double loop_sigma_meters = 0.05;
  double loop_sigma_radians = 0.01;
  // A motion edge is at least as uncertain as the filter's step and a local estimate of the same
  // step (the laser odometry's scan matching against its recent scans) disagree, once they
  // disagree by more than this many of the edge's standard deviations. Such a step is the filter
  // snapping onto an older part of its own map: a loop it closed by itself. Held at the model's
  // few centimetres and tenths of a degree, that step would tell the graph the loop is already
  // closed, the loop's error would stay in the map as a kink, and closures further along the
  // loop would fall outside their search windows or be gated. ACES on wheel odometry, seed 3:
  // the filter's first loop 15° off, closed by three such steps of 20–24°, relation error
  // 0.370 m; 0.042 m with them loosened (docs/results.md, "The filter's snaps"). Where a local
  // estimate is not given (LoopCloser::AddNode), or 0: the model's noise alone.
  double snap_sigmas = 10.0;
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
  // Measurement only (`semchain bench closures --oracle`; not read from YAML): a closure that
  // passed the score is added when this says it is true and dropped otherwise, in place of
  // verification (gate and confirmation), to measure what the map would be with a perfect
  // verifier. Called with the closure as a candidate (from, to, relative, score; the scan indices
  // where the caller knows them).
  std::function<bool(const LoopClosureCandidate&)> oracle;
  // Measurement only (`semchain bench closures --oracle-poses`; not read from YAML): a closure
  // that passed the score goes in with the relative pose this gives (the reference's) in place
  // of its match's, and is dropped where it gives none. What the graph makes of closures that
  // are exactly right tells the back end's and the front end's share of the error from the
  // matcher's and the verifier's. Takes precedence over 'oracle'.
  std::function<std::optional<Pose2>(const LoopClosureCandidate&)> oracle_relative;

  bool Validate(std::string* error) const;
};

}  // namespace semchain::mapping
