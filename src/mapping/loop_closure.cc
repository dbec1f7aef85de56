#include "mapping/loop_closure.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <memory>
#include <optional>

#include "core/check.h"
#include "mapping/chain_uncertainty.h"
#include "mapping/loop_closure_geometry.h"
#include "mapping/loop_closure_submaps.h"
#include "mapping/match_covariance.h"
#include "mapping/ray_casting.h"

namespace semchain::mapping {

using internal::Acquire;
using internal::AgreementOnKnownCells;
using internal::Finish;
using internal::Innovation;
using internal::KnownAgreement;
using internal::LoopVariances;
using internal::LoosenSnap;
using internal::MotionEdge;
using internal::MotionNoiseScale;
using internal::PoseError;
using internal::QueryPoints;
using internal::RelativeUncertainty;
using internal::ScaledMotion;
using internal::SquaredMahalanobis;
using internal::SquaredPairDisagreement;
using internal::Submap;
using internal::UncertaintyToSubmap;
using internal::WindowFor;

namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The lowest score a match may have to be verified at all.
double VerificationFloor(const LoopClosureOptions& options) {
  return options.consistent_min_score > 0.0 ? options.consistent_min_score : options.min_score;
}

// Whether a match found with a lower bound (recording candidates) reaches 'min_score' as the
// matcher itself decides: its score is a sum of bytes (255 a point) over the points, and a
// match counts when that sum is at least ceil(min_score · 255 · points).
bool ReachesMinScore(double score, std::size_t points, double min_score) {
  const double normalizer = 255.0 * static_cast<double>(points);
  return std::llround(score * normalizer) >=
         static_cast<long long>(std::ceil(min_score * normalizer));
}

// A closure as the oracle (LoopClosureOptions::oracle) sees it.
LoopClosureCandidate AsCandidate(const PoseGraphEdge& closure, double score) {
  LoopClosureCandidate candidate;
  candidate.from = closure.from;
  candidate.to = closure.to;
  candidate.score = score;
  candidate.relative = closure.relative;
  candidate.best_of_search = true;
  candidate.passed_score = true;
  return candidate;
}

// The closure as the oracle has it (LoopClosureOptions::oracle_relative: at the relative pose
// it gives; oracle: as found), or nothing where the oracle keeps it out.
std::optional<PoseGraphEdge> OracleVerdict(const PoseGraphEdge& closure, double score,
                                           const LoopClosureOptions& options) {
  const LoopClosureCandidate candidate = AsCandidate(closure, score);
  if (options.oracle_relative) {
    const std::optional<Pose2> relative = options.oracle_relative(candidate);
    if (!relative) return std::nullopt;
    PoseGraphEdge exact = closure;
    exact.relative = *relative;
    return exact;
  }
  if (!options.oracle(candidate)) return std::nullopt;
  return closure;
}

}  // namespace

struct LoopCloser::State {
  explicit State(const LoopClosureOptions& o) : options(o) {}

  LoopClosureOptions options;
  LoopClosureStatistics stats;
  // The match points of each node's scan (robot frame): all a search needs of it once it is in
  // its submap (a fifth of the scan's memory).
  std::vector<std::vector<Eigen::Vector2d>> node_points;
  std::vector<Pose2> poses;  // the filter's, one per node (rebased when the filter follows)
  // A local estimate of each node's pose (laser odometry), where given: only its steps count.
  std::vector<std::optional<Pose2>> local;
  // Per node: the motion edge from it was loosened by LoosenSnap.
  std::vector<bool> loosened;
  std::vector<Pose2> estimate;  // the graph's
  std::vector<PoseGraphEdge> edges;
  std::vector<double> travel;
  std::vector<Submap> submaps;
  std::uint64_t tick = 0;  // counts submap uses, for the built-submap cache
  int anchor = 0;          // node of the last accepted closure
  // Closures held back, newest last, each added if a later one found soon after (but not too
  // soon) agrees with it.
  std::deque<PoseGraphEdge> pending;
  std::optional<PoseGraphEdge> last_accepted;
  // The motion edges' variance factor, re-estimated from the closures' innovations.
  std::vector<Innovation> innovations;
  double scale = 1.0;
  std::optional<ChainUncertainty> chain;
  // With options.record_candidates: every match scored (PoseGraphEdge::id indexes it).
  std::vector<LoopClosureCandidate> candidates;

  // The best match of one search over the finished submaps.
  struct BestMatch {
    Submap* submap = nullptr;  // none found
    BranchAndBoundResult match;
    RelativeUncertainty uncertainty;  // of the node relative to the submap
    int candidate = -1;               // its recorded candidate (record_candidates)
  };

  bool Add(const PreparedScan& scan, const Pose2& pose, const std::optional<Pose2>& local_pose);
  // Appends node i, the one 'scan' and 'pose' are of: its match points, the filter's pose and
  // its local estimate, the travel to it and, after the first, the motion edge from node i − 1
  // and the graph's pose. Returns i.
  std::size_t AppendNode(const PreparedScan& scan, const Pose2& pose,
                         const std::optional<Pose2>& local_pose);
  // The motion edge from node 'from' to the next at the filter's poses 'a' and 'b', loosened
  // where the filter snapped (marked in 'loosened').
  PoseGraphEdge MotionEdgeFrom(std::size_t from, const Pose2& a, const Pose2& b);
  // Puts node i's scan into the open submap, first finishing it and opening the next once it
  // spans submap_travel_meters.
  void InsertIntoSubmap(const PreparedScan& scan, std::size_t i);
  // Searches the finished submaps far enough back along the path with node i's query 'points'
  // (its time counted from 'start', when the query was made); with record_candidates records
  // every match found.
  BestMatch Search(std::size_t i, const std::vector<Eigen::Vector2d>& points,
                   std::chrono::steady_clock::time_point start);
  // Records the match of node 'node' on 'submap' as a candidate, refined as a closure is, and
  // returns its index; '*highest' is the search's highest scoring candidate so far.
  int Record(const Submap& submap, int node, const std::vector<Eigen::Vector2d>& points,
             const BranchAndBoundResult& match, int* highest);
  // The closure edge of the search's best match, refined on its submap; none when, with
  // unknown_is_neutral, too little of the query lies on cells the submap observed.
  std::optional<PoseGraphEdge> ClosureOf(const BestMatch& best, int node,
                                         const std::vector<Eigen::Vector2d>& points);
  // Whether the closure found from node i goes into the graph now: it does when neither off the
  // motion's prediction nor weak (unless every closure waits), else when a held-back closure
  // agrees with it (which then goes in first, added here) or it agrees with the last accepted
  // one; otherwise it is held back.
  bool Verify(const PoseGraphEdge& closure, std::size_t i, bool off_prediction, bool weak);
  // Adds a verified closure and optimizes; it becomes the anchor unless the optimization drops it.
  void AddClosure(const PoseGraphEdge& closure, const Innovation& innovation);
  // What verification made of a recorded closure (by its edge id).
  void SetVerification(int id, ClosureVerification verification) {
    if (id >= 0) candidates[static_cast<std::size_t>(id)].verification = verification;
  }
  // Optimizes from 'initial', drops the closures the others contradict and takes the solution;
  // returns the dropped closures' indices into 'edges' as they were before.
  std::vector<int> Optimize(const std::vector<Pose2>& initial);
};

LoopCloser::LoopCloser(const LoopClosureOptions& options)
    : state_(std::make_unique<State>(options)) {
  std::string error;
  SEMCHAIN_CHECK(options.Validate(&error));
}

LoopCloser::~LoopCloser() = default;
LoopCloser::LoopCloser(LoopCloser&&) noexcept = default;
LoopCloser& LoopCloser::operator=(LoopCloser&&) noexcept = default;

bool LoopCloser::AddNode(const PreparedScan& scan, const Pose2& filter_pose,
                         const std::optional<Pose2>& local_pose) {
  return state_->Add(scan, filter_pose, local_pose);
}

const std::vector<Pose2>& LoopCloser::estimate() const { return state_->estimate; }

const std::vector<Pose2>& LoopCloser::filter_poses() const { return state_->poses; }

std::size_t LoopCloser::size() const { return state_->estimate.size(); }

void LoopCloser::Rebase() { state_->poses = state_->estimate; }

void LoopCloser::Reoptimize(const std::vector<Pose2>& filter_poses) {
  State& state = *state_;
  SEMCHAIN_CHECK(filter_poses.size() == state.poses.size());
  const auto same = [](const Pose2& a, const Pose2& b) {
    return a.x == b.x && a.y == b.y && a.theta == b.theta;
  };
  // The same line again (a second Finish()) changes nothing.
  if (std::equal(filter_poses.begin(), filter_poses.end(), state.poses.begin(), same)) return;
  std::vector<Pose2> initial(filter_poses.size());
  for (std::size_t j = 0; j < filter_poses.size(); ++j) {
    initial[j] = state.estimate[j] * state.poses[j].Inverse() * filter_poses[j];
  }
  bool closures = false;
  for (PoseGraphEdge& edge : state.edges) {
    if (edge.loop_closure) {
      closures = true;
      continue;
    }
    const auto from = static_cast<std::size_t>(edge.from);
    edge = state.MotionEdgeFrom(from, filter_poses[from], filter_poses[from + 1]);
  }
  state.poses = filter_poses;
  if (!closures) {
    state.estimate = filter_poses;
    return;
  }
  state.Optimize(initial);
}

LoopClosureStatistics LoopCloser::statistics() const {
  LoopClosureStatistics stats = state_->stats;
  stats.nodes = static_cast<int>(state_->estimate.size());
  stats.loosened =
      static_cast<int>(std::count(state_->loosened.begin(), state_->loosened.end(), true));
  stats.motion_noise_scale = state_->scale;
  stats.submaps = static_cast<int>(state_->submaps.size());
  for (const PoseGraphEdge& edge : state_->edges) {
    if (edge.loop_closure)
      stats.residuals.push_back(WhitenedResidual(edge, state_->estimate).norm());
  }
  stats.accepted = static_cast<int>(stats.residuals.size());
  return stats;
}

std::vector<LoopClosureCandidate> LoopCloser::candidates() const {
  std::vector<LoopClosureCandidate> candidates = state_->candidates;
  for (const PoseGraphEdge& edge : state_->edges) {
    if (!edge.loop_closure || edge.id < 0) continue;
    LoopClosureCandidate& candidate = candidates[static_cast<std::size_t>(edge.id)];
    const double squared = WhitenedResidual(edge, state_->estimate).squaredNorm();
    candidate.in_graph = true;
    candidate.residual_sigmas = std::sqrt(squared);
    candidate.weight = LoopEdgeWeight(state_->options.optimizer, squared);
  }
  return candidates;
}

bool LoopCloser::State::Add(const PreparedScan& scan, const Pose2& pose,
                            const std::optional<Pose2>& local_pose) {
  const std::size_t i = AppendNode(scan, pose, local_pose);
  InsertIntoSubmap(scan, i);
  if (i % static_cast<std::size_t>(options.search_every_nodes) != 0) return false;
  const auto search_start = std::chrono::steady_clock::now();
  const std::vector<Eigen::Vector2d> points =
      QueryPoints(node_points, estimate, travel, i, options);
  if (static_cast<int>(points.size()) < options.min_points) return false;
  const BestMatch best = Search(i, points, search_start);
  if (best.submap == nullptr) return false;
  const std::optional<PoseGraphEdge> closure = ClosureOf(best, static_cast<int>(i), points);
  if (!closure.has_value()) return false;
  // The closure's innovation: where it puts the node against where the graph does, and the
  // closure's own variances beside those of the path it had to be explained by.
  const Pose2 graph_relative =
      estimate[static_cast<std::size_t>(closure->from)].Between(estimate[i]);
  Innovation innovation;
  innovation.error = PoseError(closure->relative, graph_relative);
  innovation.motion = best.uncertainty.motion;
  innovation.fixed = best.uncertainty.fixed + CovarianceOf(*closure);
  const double innovation_squared =
      SquaredMahalanobis(innovation.error, innovation.motion + innovation.fixed);
  if (best.candidate >= 0) {
    candidates[static_cast<std::size_t>(best.candidate)].innovation_sigmas =
        std::sqrt(innovation_squared);
  }
  if (options.oracle_relative || options.oracle) {
    const std::optional<PoseGraphEdge> verdict = OracleVerdict(*closure, best.match.score, options);
    if (!verdict) {
      ++stats.gated;
      SetVerification(closure->id, ClosureVerification::kHeldBack);
      return false;
    }
    innovation.error = PoseError(verdict->relative, graph_relative);
    AddClosure(*verdict, innovation);
    return true;
  }
  const double gate = options.gate_sigmas * options.gate_sigmas;
  const bool off_prediction = options.gate_sigmas > 0.0 && innovation_squared > gate;
  const bool weak = !ReachesMinScore(best.match.score, points.size(), options.min_score);
  if (!Verify(*closure, i, off_prediction, weak)) return false;
  AddClosure(*closure, innovation);
  return true;
}

std::size_t LoopCloser::State::AppendNode(const PreparedScan& scan, const Pose2& pose,
                                          const std::optional<Pose2>& local_pose) {
  node_points.push_back(
      SelectMatchPoints(scan, options.match_max_range_meters, options.match_beam_step).points);
  poses.push_back(pose);
  local.push_back(local_pose);
  loosened.push_back(false);
  const std::size_t i = poses.size() - 1;
  if (i == 0) {
    estimate.push_back(poses[0]);
    travel.push_back(0.0);
    chain.emplace(poses[0]);
  } else {
    travel.push_back(travel[i - 1] + (poses[i].translation() - poses[i - 1].translation()).norm());
    edges.push_back(MotionEdgeFrom(i - 1, poses[i - 1], poses[i]));
    estimate.push_back(estimate[i - 1] * edges.back().relative);
    chain->Append(estimate.back(), edges.back().sigmas.x(), edges.back().sigmas.z());
  }
  return i;
}

PoseGraphEdge LoopCloser::State::MotionEdgeFrom(std::size_t from, const Pose2& a, const Pose2& b) {
  PoseGraphEdge edge = MotionEdge(static_cast<int>(from), a, b, options);
  loosened[from] = local[from].has_value() && local[from + 1].has_value() &&
                   LoosenSnap(local[from]->Between(*local[from + 1]), options, &edge);
  return edge;
}

void LoopCloser::State::InsertIntoSubmap(const PreparedScan& scan, std::size_t i) {
  const int node = static_cast<int>(i);
  if (submaps.empty() || travel[i] - travel[static_cast<std::size_t>(submaps.back().first)] >
                             options.submap_travel_meters) {
    if (!submaps.empty()) {
      Finish(&submaps.back(), options);
      const double held = Acquire(&submaps.back(), nullptr, ++tick, &submaps, options);
      stats.built_submaps_peak_megabytes = std::max(stats.built_submaps_peak_megabytes, held);
    }
    submaps.emplace_back();
    submaps.back().first = node;
    submaps.back().grid = OccupancyGrid(options.submap_grid);
  }
  Submap& open = submaps.back();
  open.last = node;
  InsertScan(scan, poses[static_cast<std::size_t>(open.first)].Between(poses[i]), &open.grid);
}

LoopCloser::State::BestMatch LoopCloser::State::Search(
    std::size_t i, const std::vector<Eigen::Vector2d>& points,
    std::chrono::steady_clock::time_point start) {
  const int node = static_cast<int>(i);
  const bool record = options.record_candidates;
  const double floor = VerificationFloor(options);
  bool searched = false;
  BestMatch best;
  int highest = -1;  // the recorded candidate of this search scoring highest
  for (Submap& submap : submaps) {
    if (!submap.finished || travel[i] - travel[static_cast<std::size_t>(submap.last)] <
                                options.min_loop_travel_meters) {
      continue;
    }
    const RelativeUncertainty uncertainty =
        UncertaintyToSubmap(*chain, submap.first, anchor, node, options);
    SearchWindow window = WindowFor(uncertainty.Total(), options);
    window.center = estimate[static_cast<std::size_t>(submap.first)].Between(estimate[i]);
    const double reach = window.linear_window_meters + submap.radius;
    if ((window.center.translation() - submap.center).norm() > reach) continue;
    // The best submap so far stays built: its match grid refines the closure.
    const double held = Acquire(&submap, best.submap, ++tick, &submaps, options);
    stats.built_submaps_peak_megabytes = std::max(stats.built_submaps_peak_megabytes, held);
    searched = true;
    // Recording, every submap is searched down to the recording floor; the closure picked
    // is the same (the matcher finds the same best pose above any lower bound).
    const double bound =
        record ? std::min(options.record_min_score, floor) : std::max(floor, best.match.score);
    const BranchAndBoundResult match = submap.matcher->Match(points, window, bound);
    if (!match.found) continue;
    if (record) {
      const int index = Record(submap, node, points, match, &highest);
      if (!ReachesMinScore(match.score, points.size(), floor)) continue;
      if (match.score > best.match.score) best.candidate = index;
    }
    if (match.score > best.match.score) {
      best.match = match;
      best.submap = &submap;
      best.uncertainty = uncertainty;
    }
  }
  if (highest >= 0) candidates[static_cast<std::size_t>(highest)].best_of_search = true;
  stats.search_seconds += SecondsSince(start);
  if (searched) ++stats.searches;
  return best;
}

int LoopCloser::State::Record(const Submap& submap, int node,
                              const std::vector<Eigen::Vector2d>& points,
                              const BranchAndBoundResult& match, int* highest) {
  LoopClosureCandidate candidate;
  candidate.from = submap.first;
  candidate.to = node;
  candidate.submap = static_cast<int>(&submap - submaps.data());
  candidate.score = match.score;
  candidate.relative =
      RefineWithCeres(*submap.match_grid, points, match.pose, options.refinement).pose;
  candidates.push_back(candidate);
  const int index = static_cast<int>(candidates.size()) - 1;
  if (*highest < 0 || match.score > candidates[static_cast<std::size_t>(*highest)].score) {
    *highest = index;
  }
  return index;
}

std::optional<PoseGraphEdge> LoopCloser::State::ClosureOf(
    const BestMatch& best, int node, const std::vector<Eigen::Vector2d>& points) {
  PoseGraphEdge closure;
  closure.from = best.submap->first;
  closure.to = node;
  closure.relative =
      RefineWithCeres(*best.submap->match_grid, points, best.match.pose, options.refinement).pose;
  closure.id = best.candidate;
  if (options.unknown_is_neutral) {
    const KnownAgreement agreement = AgreementOnKnownCells(*best.submap, points, closure.relative);
    if (agreement.fraction < options.min_known_fraction ||
        agreement.score < VerificationFloor(options)) {
      return std::nullopt;
    }
  }
  ++stats.found;
  if (closure.id >= 0) candidates[static_cast<std::size_t>(closure.id)].passed_score = true;
  closure.sigmas = Eigen::Vector3d(options.loop_sigma_meters, options.loop_sigma_meters,
                                   options.loop_sigma_radians);
  if (options.match_covariance) {
    closure.covariance =
        MatchCovariance(*best.submap->match_grid, points, closure.relative, options.covariance);
    closure.covariance.diagonal() += LoopVariances(options);
  }
  closure.loop_closure = true;
  return closure;
}

bool LoopCloser::State::Verify(const PoseGraphEdge& closure, std::size_t i, bool off_prediction,
                               bool weak) {
  const double gate = options.gate_sigmas * options.gate_sigmas;
  // Travel from an earlier closure's node to this one, and whether that closure says the same
  // of the map as this one.
  const auto travel_since = [&](const PoseGraphEdge& other) {
    return travel[i] - travel[static_cast<std::size_t>(other.to)];
  };
  const auto agrees_with = [&](const PoseGraphEdge& other) {
    return SquaredPairDisagreement(other, closure, estimate, *chain, options) <= gate;
  };
  while (!pending.empty() && travel_since(pending.front()) > options.confirm_within_meters) {
    pending.pop_front();
  }
  if (!off_prediction && !weak && !options.confirm_every_closure) return true;
  // Off the motion's prediction: a lone aliased match, or drift the motion model does not
  // cover. Drift makes the next closures agree with this one; aliasing does not. Within the
  // prediction, a loose motion model (a long loop) can still admit an aliased match down a
  // corridor; its neighbours then disagree with it by metres. A confirmation must come from
  // a query at least confirm_min_separation_meters further on (two scans a metre apart see
  // the same stretch of corridor and slide along it together) and, with the corridor rules,
  // for a closure off the prediction from another submap. Without them only the latest
  // held-back closure may be confirmed. A weak match (under min_score) is verified the same
  // way: by a later closure that agrees, or by agreeing with the last one accepted.
  const bool corridor = options.corridor_confirmation;
  const auto candidates_end =
      corridor || pending.empty() ? pending.rend() : std::next(pending.rbegin());
  const auto confirming = std::find_if(pending.rbegin(), candidates_end, [&](const auto& p) {
    return travel_since(p) >= options.confirm_min_separation_meters &&
           (!corridor || !off_prediction || p.from != closure.from) && agrees_with(p);
  });
  if (confirming != candidates_end) {
    --stats.gated;  // the pending closure is added after all
    edges.push_back(*confirming);
    SetVerification(confirming->id, ClosureVerification::kConfirmed);
    pending.clear();
    return true;
  }
  if (off_prediction || !last_accepted.has_value() ||
      travel_since(*last_accepted) > options.confirm_within_meters ||
      !agrees_with(*last_accepted)) {
    if (!corridor) pending.clear();  // it replaces the earlier one
    pending.push_back(closure);
    SetVerification(closure.id, ClosureVerification::kHeldBack);
    ++stats.gated;
    return false;
  }
  return true;
}

void LoopCloser::State::AddClosure(const PoseGraphEdge& closure, const Innovation& innovation) {
  edges.push_back(closure);
  SetVerification(closure.id, ClosureVerification::kAdded);
  const std::size_t closure_index = edges.size() - 1;
  if (options.adapt_motion_noise) {
    innovations.push_back(innovation);
    scale = MotionNoiseScale(innovations, options.min_motion_noise_scale,
                             options.max_motion_noise_scale);
  }
  const std::vector<int> rejected = Optimize(estimate);
  if (std::find(rejected.begin(), rejected.end(), static_cast<int>(closure_index)) ==
      rejected.end()) {
    anchor = closure.to;
    last_accepted = closure;
  }
}

std::vector<int> LoopCloser::State::Optimize(const std::vector<Pose2>& initial) {
  const GatedPoseGraphSolution gated =
      OptimizeRejectingInconsistent(initial, ScaledMotion(edges, scale, loosened),
                                    options.max_residual_sigmas, options.optimizer);
  ++stats.optimizations;
  stats.optimizer_seconds += gated.solution.seconds;
  std::vector<bool> drop(edges.size(), false);
  for (const int rejected : gated.rejected) drop[static_cast<std::size_t>(rejected)] = true;
  std::vector<PoseGraphEdge> kept;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if (!drop[e]) kept.push_back(edges[e]);
  }
  edges = std::move(kept);
  stats.rejected += static_cast<int>(gated.rejected.size());
  // The solution was found without the rejected edges (the last solve), so it stands.
  estimate = gated.solution.poses;
  chain->Reposition(estimate);
  return gated.rejected;
}

LoopClosureResult CloseLoops(const std::vector<const PreparedScan*>& scans,
                             const std::vector<Pose2>& poses, const std::vector<Pose2>& local_poses,
                             const LoopClosureOptions& options,
                             const std::function<void(std::size_t)>& progress) {
  SEMCHAIN_CHECK(scans.size() == poses.size());
  SEMCHAIN_CHECK(local_poses.empty() || local_poses.size() == poses.size());
  LoopCloser closer(options);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (progress && i > 0) progress(i);
    std::optional<Pose2> local;
    if (!local_poses.empty()) local = local_poses[i];
    closer.AddNode(*scans[i], poses[i], local);
  }
  if (progress) progress(poses.size());
  return {closer.estimate(), closer.statistics(), closer.candidates()};
}

LoopClosureResult CloseLoops(const std::vector<const PreparedScan*>& scans,
                             const std::vector<Pose2>& poses, const LoopClosureOptions& options,
                             const std::function<void(std::size_t)>& progress) {
  return CloseLoops(scans, poses, {}, options, progress);
}

}  // namespace semchain::mapping
