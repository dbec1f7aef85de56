#include "mapping/loop_closure_submaps.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace semchain::mapping::internal {
namespace {

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

double BuiltMegabytes(const Submap& submap) {
  const std::size_t bytes =
      submap.match_grid->values.size() * sizeof(float) + submap.matcher->precomputation_bytes();
  return static_cast<double>(bytes) / (1024.0 * 1024.0);
}

}  // namespace

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

}  // namespace semchain::mapping::internal
