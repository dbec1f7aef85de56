#include "mapping/loop_closure.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <memory>
#include <optional>
#include <unordered_set>

#include "core/angles.h"
#include "core/check.h"
#include "mapping/chain_uncertainty.h"
#include "mapping/map_io.h"
#include "mapping/ray_casting.h"

namespace semchain::mapping {

bool LoopClosureOptions::Validate(std::string* error) const {
  if (!(submap_travel_meters > 0.0)) {
    *error = "submap_travel_meters must be positive";
    return false;
  }
  if (!(min_loop_travel_meters > 0.0)) {
    *error = "min_loop_travel_meters must be positive";
    return false;
  }
  if (search_every_nodes < 1) {
    *error = "search_every_nodes must be >= 1";
    return false;
  }
  if (max_built_submaps < 1) {
    *error = "max_built_submaps must be >= 1";
    return false;
  }
  if (!(max_built_submaps_megabytes > 0.0)) {
    *error = "max_built_submaps_megabytes must be positive";
    return false;
  }
  if (!(window_sigmas > 0.0)) {
    *error = "window_sigmas must be positive";
    return false;
  }
  if (!(gate_sigmas >= 0.0)) {
    *error = "gate_sigmas must be >= 0 (0: no gate)";
    return false;
  }
  if (!(confirm_within_meters >= 0.0)) {
    *error = "confirm_within_meters must be >= 0";
    return false;
  }
  if (!(linear_window_meters > 0.0) || !(max_linear_window_meters >= linear_window_meters)) {
    *error = "linear windows must be positive and max_linear_window_meters >= linear_window_meters";
    return false;
  }
  if (!(angular_window_radians > 0.0) || !(max_angular_window_radians >= angular_window_radians)) {
    *error =
        "angular windows must be positive and max_angular_window_radians >= angular_window_radians";
    return false;
  }
  if (!(min_score > 0.0 && min_score <= 1.0)) {
    *error = "min_score must be in (0, 1]";
    return false;
  }
  if (!(odometry_sigma_meters > 0.0) || !(odometry_sigma_radians > 0.0) ||
      !(loop_sigma_meters > 0.0) || !(loop_sigma_radians > 0.0) ||
      !(odometry_sigma_per_meter >= 0.0) || !(odometry_sigma_radians_per_radian >= 0.0)) {
    *error = "sigmas must be positive";
    return false;
  }
  if (!(min_motion_noise_scale > 0.0) || !(max_motion_noise_scale >= min_motion_noise_scale)) {
    *error = "motion noise scales must be positive and max >= min";
    return false;
  }
  if (!(min_known_fraction >= 0.0 && min_known_fraction <= 1.0)) {
    *error = "min_known_fraction must be in [0, 1]";
    return false;
  }
  if (!(consistent_min_score >= 0.0 && consistent_min_score <= min_score)) {
    *error = "consistent_min_score must be in [0, min_score]";
    return false;
  }
  if (!(query_travel_meters >= 0.0) || !(query_cell_meters > 0.0)) {
    *error = "query_travel_meters must be >= 0 and query_cell_meters positive";
    return false;
  }
  if (online_lag_nodes < 0) {
    *error = "online_lag_nodes must be >= 0";
    return false;
  }
  if (!(follow_min_shift_meters > 0.0) || !(follow_min_turn_radians > 0.0)) {
    *error = "follow_min_shift_meters and follow_min_turn_radians must be positive";
    return false;
  }
  if (!(record_min_score > 0.0 && record_min_score <= 1.0)) {
    *error = "record_min_score must be in (0, 1]";
    return false;
  }
  if (!(max_residual_sigmas > 0.0)) {
    *error = "max_residual_sigmas must be positive";
    return false;
  }
  if (!submap_grid.Validate(error) || !match_grid.Validate(error) || !matcher.Validate(error) ||
      !refinement.Validate(error)) {
    return false;
  }
  return optimizer.Validate(error);
}

// Kept by LoopCloser::State (a member of a class with linkage may not use the anonymous
// namespace).
namespace loop_closure_internal {

// A rigid local map in the frame of its first node.
struct Submap {
  int first = 0;
  int last = 0;
  // While open: the grid scans go into. Once finished it keeps only its frame (an empty grid
  // with the same origin and resolution, for CellOf): what the searches need of it is kept as
  // an image at a byte a cell, where the grid takes 16 (a campus run has a hundred submaps).
  OccupancyGrid grid;
  bool finished = false;
  // Once finished: the grid's image (the match grid is built from it) and, cell by cell over its
  // extent, whether the grid observed the cell (the image's unknown also covers observed cells
  // of middling probability; a bit a cell: MIT Killian's masks took 50 MB as bytes);
  // image_min is its first cell in the grid's indices.
  MapImage image;
  std::vector<bool> observed;
  Eigen::Vector2i image_min = Eigen::Vector2i::Zero();
  // Once finished: the match grid's centre and the radius of its extent around it (metres)...
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 0.0;
  // ...and, while built, the match grid and its matcher (which refers to the grid).
  std::unique_ptr<MatchGrid> match_grid;
  std::unique_ptr<BranchAndBoundMatcher> matcher;
  std::uint64_t last_used = 0;  // search counter when it was last needed built
};

// What an accepted closure said that the graph did not already know: its error against the
// graph's prediction and the two covariances that error had to be explained by.
struct Innovation {
  Eigen::Vector3d error;
  Eigen::Matrix3d motion;  // the motion edges' part, at their modelled variances
  Eigen::Matrix3d fixed;   // the closures' part
};

}  // namespace loop_closure_internal

using loop_closure_internal::Innovation;
using loop_closure_internal::Submap;

namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void Build(Submap* submap, const LoopClosureOptions& options) {
  const MapImage& image = submap->image;
  MatchGridOptions search_options = options.match_grid;
  // Just below min_score in the matcher's byte scale: a pose whose returns all fall on unknown
  // cells is never a candidate, so branch-and-bound prunes such nodes from the start.
  if (options.unknown_is_neutral) {
    search_options.unknown_value = (std::ceil(options.min_score * 255.0) - 1.0) / 255.0;
  }
  submap->match_grid = std::make_unique<MatchGrid>(MakeMatchGrid(image, search_options));
  submap->matcher = std::make_unique<BranchAndBoundMatcher>(*submap->match_grid, options.matcher);
}

// Whether the finished submap's grid observed the cell holding 'point' (submap frame).
bool Observed(const Submap& submap, const Eigen::Vector2d& point) {
  const Eigen::Vector2i cell = submap.grid.CellOf(point) - submap.image_min;
  if (cell.x() < 0 || cell.y() < 0 || cell.x() >= submap.image.width ||
      cell.y() >= submap.image.height) {
    return false;
  }
  return submap.observed[static_cast<std::size_t>(cell.y() * submap.image.width + cell.x())];
}

void Finish(Submap* submap, const LoopClosureOptions& options) {
  const OccupancyGrid& grid = submap->grid;
  submap->image = GridToMapImage(grid);
  const Eigen::Vector2d offset =
      (submap->image.origin.head<2>() - grid.origin()) / grid.resolution();
  submap->image_min = Eigen::Vector2i(static_cast<int>(std::lround(offset.x())),
                                      static_cast<int>(std::lround(offset.y())));
  submap->observed.assign(submap->image.cells.size(), false);
  for (int y = 0; y < submap->image.height; ++y) {
    for (int x = 0; x < submap->image.width; ++x) {
      const GridCell* cell = grid.Find(submap->image_min + Eigen::Vector2i(x, y));
      submap->observed[static_cast<std::size_t>(y * submap->image.width + x)] =
          cell != nullptr && cell->Known();
    }
  }
  submap->grid = OccupancyGrid(grid.options(), grid.origin());
  Build(submap, options);
  submap->finished = true;
  submap->center = submap->match_grid->Center();
  submap->radius = 0.5 * submap->match_grid->resolution *
                   std::hypot(submap->match_grid->width, submap->match_grid->height);
}

double BuiltMegabytes(const Submap& submap) {
  const std::size_t bytes =
      submap.match_grid->values.size() * sizeof(float) + submap.matcher->precomputation_bytes();
  return static_cast<double>(bytes) / (1024.0 * 1024.0);
}

// Builds 'wanted' if needed and marks it used at 'tick'; then, while more than
// options.max_built_submaps finished submaps are built, or they hold more than
// options.max_built_submaps_megabytes, frees the least recently used one other than 'wanted' and
// 'keep' (may be null). Returns the most the built submaps held (once 'wanted' was built).
double Acquire(Submap* wanted, const Submap* keep, std::uint64_t tick, std::vector<Submap>* submaps,
               const LoopClosureOptions& options) {
  if (!wanted->matcher) Build(wanted, options);
  wanted->last_used = tick;
  double most = 0.0;
  while (true) {
    Submap* oldest = nullptr;
    int built = 0;
    double megabytes = 0.0;
    for (Submap& submap : *submaps) {
      if (!submap.matcher) continue;
      ++built;
      megabytes += BuiltMegabytes(submap);
      if (&submap == wanted || &submap == keep) continue;
      if (oldest == nullptr || submap.last_used < oldest->last_used) oldest = &submap;
    }
    most = std::max(most, megabytes);
    if ((built <= options.max_built_submaps && megabytes <= options.max_built_submaps_megabytes) ||
        oldest == nullptr) {
      return most;
    }
    oldest->matcher.reset();
    oldest->match_grid.reset();
  }
}

// The match points of node i's scan and, with query_travel_meters > 0, of the scans of the nodes
// before it within that much travel, in node i's frame (placed by the graph's estimate), at most
// one per query_cell_meters cell. Down a corridor one scan sees few of the features that tell
// places apart (a 180° laser mostly sees the walls beside it); a short stretch of the local map
// sees each several times.
std::vector<Eigen::Vector2d> QueryPoints(
    const std::vector<std::vector<Eigen::Vector2d>>& node_points,
    const std::vector<Pose2>& estimate, const std::vector<double>& travel, std::size_t i,
    const LoopClosureOptions& options) {
  if (options.query_travel_meters <= 0.0) return node_points[i];
  std::vector<Eigen::Vector2d> query;
  std::unordered_set<std::int64_t> cells;
  const double per_cell = 1.0 / options.query_cell_meters;
  const auto add = [&](const Eigen::Vector2d& point) {
    const auto cx = static_cast<std::int64_t>(std::floor(point.x() * per_cell));
    const auto cy = static_cast<std::int64_t>(std::floor(point.y() * per_cell));
    if (cells.insert((cx << 32) ^ (cy & 0xffffffff)).second) query.push_back(point);
  };
  for (const Eigen::Vector2d& point : node_points[i]) add(point);
  for (std::size_t j = i; j-- > 0 && travel[i] - travel[j] <= options.query_travel_meters;) {
    const Eigen::Isometry2d to_node = estimate[i].Between(estimate[j]).ToIsometry();
    for (const Eigen::Vector2d& point : node_points[j]) add(to_node * point);
  }
  return query;
}

// How a query placed at 'pose' agrees with what the submap observed: the share of its points on
// observed cells and their mean M.
struct KnownAgreement {
  double fraction = 0.0;
  double score = 0.0;
};

KnownAgreement AgreementOnKnownCells(const Submap& submap,
                                     const std::vector<Eigen::Vector2d>& points,
                                     const Pose2& pose) {
  KnownAgreement agreement;
  if (points.empty()) return agreement;
  const Eigen::Isometry2d transform = pose.ToIsometry();
  int known = 0;
  double sum = 0.0;
  for (const Eigen::Vector2d& point : points) {
    const Eigen::Vector2d world = transform * point;
    if (!Observed(submap, world)) continue;
    ++known;
    const Eigen::Vector2i match_cell = submap.match_grid->CellOf(world);
    sum += submap.match_grid->At(match_cell.x(), match_cell.y());
  }
  agreement.fraction = static_cast<double>(known) / static_cast<double>(points.size());
  agreement.score = known > 0 ? sum / static_cast<double>(known) : 0.0;
  return agreement;
}

Eigen::Vector3d LoopVariances(const LoopClosureOptions& options) {
  return Eigen::Vector3d(options.loop_sigma_meters * options.loop_sigma_meters,
                         options.loop_sigma_meters * options.loop_sigma_meters,
                         options.loop_sigma_radians * options.loop_sigma_radians);
}

PoseGraphEdge MotionEdge(int from, const Pose2& a, const Pose2& b,
                         const LoopClosureOptions& options) {
  PoseGraphEdge edge;
  edge.from = from;
  edge.to = from + 1;
  edge.relative = a.Between(b);
  const double distance = edge.relative.translation().norm();
  const double turn = std::abs(edge.relative.theta);
  const double xy = options.odometry_sigma_meters + options.odometry_sigma_per_meter * distance;
  const double theta =
      options.odometry_sigma_radians + options.odometry_sigma_radians_per_radian * turn;
  edge.sigmas = Eigen::Vector3d(xy, xy, theta);
  return edge;
}

// Uncertainty of node i relative to submap 'first', in the submap's frame: the motion edges'
// part, since the later of the submap and the last accepted closure ('anchor'; the closure ties
// the path before it to the map, up to the closure's own uncertainty), and that closure's part.
struct RelativeUncertainty {
  Eigen::Matrix3d motion = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d fixed = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d Total() const { return motion + fixed; }
};

RelativeUncertainty UncertaintyToSubmap(const ChainUncertainty& chain, int first, int anchor, int i,
                                        const LoopClosureOptions& options) {
  const int from = std::max(first, anchor);
  RelativeUncertainty uncertainty{chain.Relative(from, i, first), Eigen::Matrix3d::Zero()};
  if (from != first) uncertainty.fixed.diagonal() = LoopVariances(options);
  return uncertainty;
}

SearchWindow WindowFor(const Eigen::Matrix3d& covariance, const LoopClosureOptions& options) {
  SearchWindow window;
  const double linear_sigma =
      std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(covariance.topLeftCorner<2, 2>(),
                                                               Eigen::EigenvaluesOnly)
                    .eigenvalues()
                    .maxCoeff());
  window.linear_window_meters =
      std::clamp(options.window_sigmas * linear_sigma, options.linear_window_meters,
                 options.max_linear_window_meters);
  window.angular_window_radians =
      std::clamp(options.window_sigmas * std::sqrt(covariance(2, 2)),
                 options.angular_window_radians, options.max_angular_window_radians);
  return window;
}

// (x, y, θ) of 'a' minus those of 'b', the heading wrapped.
Eigen::Vector3d PoseError(const Pose2& a, const Pose2& b) {
  return {a.x - b.x, a.y - b.y, NormalizeAngle(a.theta - b.theta)};
}

double SquaredMahalanobis(const Eigen::Vector3d& error, const Eigen::Matrix3d& covariance) {
  return error.dot(covariance.ldlt().solve(error));
}

// Squared Mahalanobis distance between what two closures say of the motion from a.to to b.to
// (each places its node in the map) and what the chain says of it; closures to two submaps also
// carry the uncertainty of the chain between the submaps (first-order, summed).
double SquaredPairDisagreement(const PoseGraphEdge& a, const PoseGraphEdge& b,
                               const std::vector<Pose2>& estimate, const ChainUncertainty& chain,
                               const LoopClosureOptions& options) {
  const auto at = [&estimate](int node) -> const Pose2& {
    return estimate[static_cast<std::size_t>(node)];
  };
  const Pose2 implied = (at(a.from) * a.relative).Between(at(b.from) * b.relative);
  Eigen::Matrix3d covariance = chain.Relative(a.to, b.to);
  if (options.corridor_confirmation && a.from != b.from) {
    covariance += chain.Relative(std::min(a.from, b.from), std::max(a.from, b.from));
  }
  covariance.diagonal() += 2.0 * LoopVariances(options);
  return SquaredMahalanobis(PoseError(implied, at(a.to).Between(at(b.to))), covariance);
}

// The smallest factor on the motion edges' variances under which every closure's innovation
// lies within the 99 % region of a 3-dof Gaussian (squared Mahalanobis distance 11.34), within
// [min_scale, max_scale]: a filter far better than the model (its closures land where it
// predicts) gets a stiffer chain, one that drifts more a looser one.
double MotionNoiseScale(const std::vector<Innovation>& innovations, double min_scale,
                        double max_scale) {
  constexpr double kChiSquared3Dof99 = 11.345;
  const auto worst = [&innovations](double scale) {
    double largest = 0.0;
    for (const Innovation& v : innovations) {
      largest = std::max(largest, SquaredMahalanobis(v.error, scale * v.motion + v.fixed));
    }
    return largest;
  };
  if (worst(min_scale) <= kChiSquared3Dof99) return min_scale;
  if (worst(max_scale) >= kChiSquared3Dof99) return max_scale;
  double low = std::log(min_scale), high = std::log(max_scale);
  for (int iteration = 0; iteration < 40; ++iteration) {
    const double middle = 0.5 * (low + high);
    (worst(std::exp(middle)) > kChiSquared3Dof99 ? low : high) = middle;
  }
  return std::exp(high);
}

// Whether a match found with a lower bound (recording candidates) reaches 'min_score' as the
// matcher itself decides: its score is a sum of bytes (255 a point) over the points, and a
// match counts when that sum is at least ceil(min_score · 255 · points).
bool ReachesMinScore(double score, std::size_t points, double min_score) {
  const double normalizer = 255.0 * static_cast<double>(points);
  return std::llround(score * normalizer) >=
         static_cast<long long>(std::ceil(min_score * normalizer));
}

// 'edges' with the motion edges' standard deviations multiplied by sqrt(scale).
std::vector<PoseGraphEdge> ScaledMotion(const std::vector<PoseGraphEdge>& edges, double scale) {
  std::vector<PoseGraphEdge> scaled = edges;
  const double factor = std::sqrt(scale);
  for (PoseGraphEdge& edge : scaled) {
    if (!edge.loop_closure) edge.sigmas *= factor;
  }
  return scaled;
}

}  // namespace

struct LoopCloser::State {
  explicit State(const LoopClosureOptions& o) : options(o) {}

  LoopClosureOptions options;
  LoopClosureStatistics stats;
  // The match points of each node's scan (robot frame): all a search needs of it once it is in
  // its submap (a fifth of the scan's memory).
  std::vector<std::vector<Eigen::Vector2d>> node_points;
  std::vector<Pose2> poses;     // the filter's, one per node (rebased when the filter follows)
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

  bool Add(const PreparedScan& scan, const Pose2& pose);
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

bool LoopCloser::AddNode(const PreparedScan& scan, const Pose2& filter_pose) {
  return state_->Add(scan, filter_pose);
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
    edge = MotionEdge(edge.from, filter_poses[static_cast<std::size_t>(edge.from)],
                      filter_poses[static_cast<std::size_t>(edge.to)], state.options);
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

bool LoopCloser::State::Add(const PreparedScan& scan, const Pose2& pose) {
  node_points.push_back(
      SelectMatchPoints(scan, options.match_max_range_meters, options.match_beam_step).points);
  poses.push_back(pose);
  const std::size_t i = poses.size() - 1;
  const int node = static_cast<int>(i);
  if (i == 0) {
    estimate.push_back(poses[0]);
    travel.push_back(0.0);
    chain.emplace(poses[0]);
  } else {
    travel.push_back(travel[i - 1] + (poses[i].translation() - poses[i - 1].translation()).norm());
    edges.push_back(MotionEdge(node - 1, poses[i - 1], poses[i], options));
    estimate.push_back(estimate[i - 1] * edges.back().relative);
    chain->Append(estimate.back(), edges.back().sigmas.x(), edges.back().sigmas.z());
  }
  // The submap this node's scan goes into.
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

  if (i % static_cast<std::size_t>(options.search_every_nodes) != 0) return false;
  const auto search_start = std::chrono::steady_clock::now();
  const std::vector<Eigen::Vector2d> points =
      QueryPoints(node_points, estimate, travel, i, options);
  if (static_cast<int>(points.size()) < options.min_points) return false;
  bool searched = false;
  Submap* best_submap = nullptr;
  BranchAndBoundResult best;
  RelativeUncertainty best_uncertainty;
  const bool record = options.record_candidates;
  // The lowest score a match may have to be verified at all.
  const double floor =
      options.consistent_min_score > 0.0 ? options.consistent_min_score : options.min_score;
  int best_candidate = -1;  // the recorded candidate of best_submap
  int highest = -1;         // the recorded candidate of this search scoring highest
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
    // The best submap so far stays built: its match grid refines the closure below.
    const double held = Acquire(&submap, best_submap, ++tick, &submaps, options);
    stats.built_submaps_peak_megabytes = std::max(stats.built_submaps_peak_megabytes, held);
    searched = true;
    // Recording, every submap is searched down to the recording floor; the closure picked
    // below is the same (the matcher finds the same best pose above any lower bound).
    const double bound =
        record ? std::min(options.record_min_score, floor) : std::max(floor, best.score);
    const BranchAndBoundResult match = submap.matcher->Match(points, window, bound);
    if (!match.found) continue;
    if (record) {
      LoopClosureCandidate candidate;
      candidate.from = submap.first;
      candidate.to = node;
      candidate.submap = static_cast<int>(&submap - submaps.data());
      candidate.score = match.score;
      candidate.relative =
          RefineWithCeres(*submap.match_grid, points, match.pose, options.refinement).pose;
      candidates.push_back(candidate);
      const int index = static_cast<int>(candidates.size()) - 1;
      if (highest < 0 || match.score > candidates[static_cast<std::size_t>(highest)].score) {
        highest = index;
      }
      if (!ReachesMinScore(match.score, points.size(), floor)) continue;
      if (match.score > best.score) best_candidate = index;
    }
    if (match.score > best.score) {
      best = match;
      best_submap = &submap;
      best_uncertainty = uncertainty;
    }
  }
  if (highest >= 0) candidates[static_cast<std::size_t>(highest)].best_of_search = true;
  stats.search_seconds += SecondsSince(search_start);
  if (searched) ++stats.searches;
  if (best_submap == nullptr) return false;
  PoseGraphEdge closure;
  closure.from = best_submap->first;
  closure.to = node;
  closure.relative =
      RefineWithCeres(*best_submap->match_grid, points, best.pose, options.refinement).pose;
  closure.id = best_candidate;
  LoopClosureCandidate* candidate =
      best_candidate >= 0 ? &candidates[static_cast<std::size_t>(best_candidate)] : nullptr;
  // What verification made of a recorded closure (by its edge id).
  const auto verified = [this](int id, ClosureVerification verification) {
    if (id >= 0) candidates[static_cast<std::size_t>(id)].verification = verification;
  };
  if (options.unknown_is_neutral) {
    const KnownAgreement agreement = AgreementOnKnownCells(*best_submap, points, closure.relative);
    if (agreement.fraction < options.min_known_fraction || agreement.score < floor) {
      return false;
    }
  }
  ++stats.found;
  if (candidate != nullptr) candidate->passed_score = true;
  closure.sigmas = Eigen::Vector3d(options.loop_sigma_meters, options.loop_sigma_meters,
                                   options.loop_sigma_radians);
  closure.loop_closure = true;
  const double gate = options.gate_sigmas * options.gate_sigmas;
  // The closure's innovation: where it puts the node against where the graph does, and the
  // closure's own variances beside those of the path it had to be explained by.
  Innovation innovation;
  innovation.error = PoseError(
      closure.relative, estimate[static_cast<std::size_t>(closure.from)].Between(estimate[i]));
  innovation.motion = best_uncertainty.motion;
  innovation.fixed = best_uncertainty.fixed;
  innovation.fixed.diagonal() += LoopVariances(options);
  const double innovation_squared =
      SquaredMahalanobis(innovation.error, innovation.motion + innovation.fixed);
  if (candidate != nullptr) candidate->innovation_sigmas = std::sqrt(innovation_squared);
  const bool off_prediction = options.gate_sigmas > 0.0 && innovation_squared > gate;
  const bool weak = !ReachesMinScore(best.score, points.size(), options.min_score);
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
  if (off_prediction || weak || options.confirm_every_closure) {
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
      verified(confirming->id, ClosureVerification::kConfirmed);
      pending.clear();
    } else if (off_prediction || !last_accepted.has_value() ||
               travel_since(*last_accepted) > options.confirm_within_meters ||
               !agrees_with(*last_accepted)) {
      if (!corridor) pending.clear();  // it replaces the earlier one
      pending.push_back(closure);
      verified(closure.id, ClosureVerification::kHeldBack);
      ++stats.gated;
      return false;
    }
  }
  edges.push_back(closure);
  verified(closure.id, ClosureVerification::kAdded);
  const std::size_t closure_index = edges.size() - 1;
  if (options.adapt_motion_noise) {
    innovations.push_back(innovation);
    scale = MotionNoiseScale(innovations, options.min_motion_noise_scale,
                             options.max_motion_noise_scale);
  }
  const std::vector<int> rejected = Optimize(estimate);
  if (std::find(rejected.begin(), rejected.end(), static_cast<int>(closure_index)) ==
      rejected.end()) {
    anchor = node;
    last_accepted = closure;
  }
  return true;
}

std::vector<int> LoopCloser::State::Optimize(const std::vector<Pose2>& initial) {
  const GatedPoseGraphSolution gated = OptimizeRejectingInconsistent(
      initial, ScaledMotion(edges, scale), options.max_residual_sigmas, options.optimizer);
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
                             const std::vector<Pose2>& poses, const LoopClosureOptions& options,
                             const std::function<void(std::size_t)>& progress) {
  SEMCHAIN_CHECK(scans.size() == poses.size());
  LoopCloser closer(options);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (progress && i > 0) progress(i);
    closer.AddNode(*scans[i], poses[i]);
  }
  if (progress) progress(poses.size());
  return {closer.estimate(), closer.statistics(), closer.candidates()};
}

}  // namespace semchain::mapping
