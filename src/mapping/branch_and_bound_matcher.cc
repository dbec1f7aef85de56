#include "mapping/branch_and_bound_matcher.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"
#include "core/check.h"
#include "core/cpu_time.h"

namespace semchain::mapping {
namespace {

// One node of the search tree: a heading and the lowest translation offset (cells) of the
// 2^h × 2^h block of translations it covers.
struct Candidate {
  int angle = 0;  // index into Discretization::angles
  int dx = 0;
  int dy = 0;
  std::int64_t sum = 0;  // Σ precomputation-grid values over the points
};

bool Better(const Candidate& a, const Candidate& b) { return a.sum > b.sum; }

}  // namespace

bool BranchAndBoundOptions::Validate(std::string* error) const {
  if (branch_and_bound_depth < 0 || branch_and_bound_depth > 14) {
    *error = "branch_and_bound_depth must be in [0, 14]";
    return false;
  }
  if (!(angular_step_radians >= 0.0)) {
    *error = "angular_step_radians must be >= 0";
    return false;
  }
  return true;
}

// The scan rotated to every searched heading and placed at the window centre, in cells; the
// translation offsets then only shift cell indices.
struct BranchAndBoundMatcher::Discretization {
  Pose2 center;
  double resolution = 0.05;
  std::vector<double> angles;                       // absolute headings
  std::vector<std::vector<Eigen::Vector2i>> cells;  // per heading, per point
  int min_x = 0, max_x = 0, min_y = 0, max_y = 0;   // translation offsets, cells
  bool every_heading = false;                       // the headings go all the way round

  std::int64_t Sum(const PrecomputationGrid& grid, const Candidate& c) const {
    std::int64_t sum = 0;
    for (const Eigen::Vector2i& cell : cells[static_cast<std::size_t>(c.angle)]) {
      sum += grid.At(cell.x() + c.dx, cell.y() + c.dy);
    }
    return sum;
  }
  bool OnLinearEdge(const Candidate& c) const {
    return c.dx == min_x || c.dx == max_x || c.dy == min_y || c.dy == max_y;
  }
  bool OnAngularEdge(const Candidate& c) const {
    return !every_heading && (c.angle == 0 || c.angle + 1 == static_cast<int>(angles.size()));
  }
  Pose2 PoseOf(const Candidate& c) const {
    return Pose2(center.x + c.dx * resolution, center.y + c.dy * resolution,
                 angles[static_cast<std::size_t>(c.angle)]);
  }
};

BranchAndBoundMatcher::BranchAndBoundMatcher(const MatchGrid& grid,
                                             const BranchAndBoundOptions& options)
    : grid_(grid), options_(options), stack_(grid, options.branch_and_bound_depth) {
  std::string error;
  SEMCHAIN_CHECK(options_.Validate(&error));
}

BranchAndBoundMatcher::Discretization BranchAndBoundMatcher::Discretize(
    const std::vector<Eigen::Vector2d>& points, const SearchWindow& window) const {
  Discretization d;
  d.center = window.center;
  d.resolution = grid_.resolution;
  double step = options_.angular_step_radians;
  if (step <= 0.0) {
    double farthest = grid_.resolution;
    for (const Eigen::Vector2d& p : points) farthest = std::max(farthest, p.norm());
    const double r = grid_.resolution;
    step = std::acos(1.0 - r * r / (2.0 * farthest * farthest));
  }
  d.every_heading = window.angular_window_radians >= kPi;
  if (d.every_heading) {
    const int n = static_cast<int>(std::ceil(kPi / step));
    for (int i = -n + 1; i <= n; ++i) d.angles.push_back(window.center.theta + i * (kPi / n));
  } else {
    const int n = static_cast<int>(std::ceil(window.angular_window_radians / step));
    const int searched =
        window.searched_angular_window_radians > 0.0
            ? static_cast<int>(std::ceil(window.searched_angular_window_radians / step))
            : -1;
    for (int i = -n; i <= n; ++i) {
      if (std::abs(i) > searched) d.angles.push_back(window.center.theta + i * step);
    }
  }
  for (const double theta : d.angles) {
    const Eigen::Isometry2d pose = Pose2(window.center.x, window.center.y, theta).ToIsometry();
    std::vector<Eigen::Vector2i>& cells = d.cells.emplace_back();
    cells.reserve(points.size());
    for (const Eigen::Vector2d& p : points) cells.push_back(grid_.CellOf(pose * p));
  }
  const int n = static_cast<int>(std::ceil(window.linear_window_meters / grid_.resolution));
  d.min_x = d.min_y = -n;
  d.max_x = d.max_y = n;
  return d;
}

BranchAndBoundResult BranchAndBoundMatcher::Match(const std::vector<Eigen::Vector2d>& points,
                                                  const SearchWindow& window, double min_score,
                                                  const TranslationPyramid* allowed) const {
  const double start = ProcessCpuSeconds();
  BranchAndBoundResult result;
  if (points.empty()) return result;
  const Discretization d = Discretize(points, window);
  // Roots no larger than the window: a root covering far more than the window has a loose
  // bound (the best value over cells never searched) and only adds levels that cannot prune.
  int depth = 0;
  while (depth < stack_.max_depth() && (1 << depth) < d.max_x - d.min_x + 1) ++depth;
  const double normalizer = 255.0 * static_cast<double>(points.size());
  // A node may hold the robot when its block of translations holds an allowed cell (levels the
  // pyramid lacks are not checked).
  const Eigen::Vector2i center_cell = grid_.CellOf(window.center.translation());
  const auto may_hold_robot = [&](int dx, int dy, int height) {
    return allowed == nullptr || height > allowed->max_depth() ||
           allowed->Any(height, center_cell.x() + dx, center_cell.y() + dy);
  };
  const auto score_all = [&](std::vector<Candidate>& candidates, int height) {
    const PrecomputationGrid& grid = stack_.Get(height);
    for (Candidate& c : candidates) c.sum = d.Sum(grid, c);
    result.nodes_scored += static_cast<std::int64_t>(candidates.size());
    std::sort(candidates.begin(), candidates.end(), Better);
  };
  // Root nodes: every heading, translations in steps of 2^depth (Hess et al. Algorithm 3).
  std::vector<Candidate> roots;
  const int root_step = 1 << depth;
  for (int a = 0; a < static_cast<int>(d.angles.size()); ++a) {
    for (int dx = d.min_x; dx <= d.max_x; dx += root_step) {
      for (int dy = d.min_y; dy <= d.max_y; dy += root_step) {
        if (may_hold_robot(dx, dy, depth)) roots.push_back({a, dx, dy, 0});
      }
    }
  }
  score_all(roots, depth);
  result.root_nodes = static_cast<std::int64_t>(roots.size());
  result.angles = static_cast<int>(d.angles.size());

  // Depth-first, best child first; a node whose bound does not beat the best leaf is pruned.
  std::int64_t best_sum = static_cast<std::int64_t>(std::ceil(min_score * normalizer)) - 1;
  std::optional<Candidate> best;
  const auto search = [&](auto&& self, const std::vector<Candidate>& candidates,
                          int height) -> void {
    for (const Candidate& c : candidates) {
      if (c.sum <= best_sum) break;  // sorted: no later node can do better
      if (height == 0) {
        best_sum = c.sum;
        best = c;
        continue;
      }
      const int half = 1 << (height - 1);
      std::vector<Candidate> children;
      for (const int ox : {0, half}) {
        if (c.dx + ox > d.max_x) break;
        for (const int oy : {0, half}) {
          if (c.dy + oy > d.max_y) break;
          if (!may_hold_robot(c.dx + ox, c.dy + oy, height - 1)) continue;
          children.push_back({c.angle, c.dx + ox, c.dy + oy, 0});
        }
      }
      score_all(children, height - 1);
      self(self, children, height - 1);
    }
  };
  search(search, roots, depth);
  if (best) {
    result.found = true;
    result.pose = d.PoseOf(*best);
    result.score = static_cast<double>(best->sum) / normalizer;
    result.on_linear_edge = d.OnLinearEdge(*best);
    result.on_angular_edge = d.OnAngularEdge(*best);
  }
  result.cpu_seconds = ProcessCpuSeconds() - start;
  return result;
}

BranchAndBoundResult BranchAndBoundMatcher::MatchFullMap(const std::vector<Eigen::Vector2d>& points,
                                                         double min_score,
                                                         const TranslationPyramid* allowed) const {
  SearchWindow window;
  const Eigen::Vector2d center = grid_.Center();
  window.center = Pose2(center.x(), center.y(), 0.0);
  // Half the larger side plus one cell: every robot position on the map is searched.
  window.linear_window_meters =
      0.5 * std::max(grid_.width, grid_.height) * grid_.resolution + grid_.resolution;
  window.angular_window_radians = kPi;
  return Match(points, window, min_score, allowed);
}

BranchAndBoundResult BranchAndBoundMatcher::MatchExhaustive(
    const std::vector<Eigen::Vector2d>& points, const SearchWindow& window) const {
  const double start = ProcessCpuSeconds();
  BranchAndBoundResult result;
  if (points.empty()) return result;
  const Discretization d = Discretize(points, window);
  const PrecomputationGrid& grid = stack_.Get(0);
  Candidate best{0, 0, 0, -1};
  for (int a = 0; a < static_cast<int>(d.angles.size()); ++a) {
    for (int dx = d.min_x; dx <= d.max_x; ++dx) {
      for (int dy = d.min_y; dy <= d.max_y; ++dy) {
        Candidate c{a, dx, dy, 0};
        c.sum = d.Sum(grid, c);
        ++result.nodes_scored;
        if (c.sum > best.sum) best = c;
      }
    }
  }
  result.found = true;
  result.pose = d.PoseOf(best);
  result.on_linear_edge = d.OnLinearEdge(best);
  result.on_angular_edge = d.OnAngularEdge(best);
  result.score = static_cast<double>(best.sum) / (255.0 * static_cast<double>(points.size()));
  result.angles = static_cast<int>(d.angles.size());
  result.cpu_seconds = ProcessCpuSeconds() - start;
  return result;
}

}  // namespace semchain::mapping
