#pragma once

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "mapping/map_io.h"

// The map a scan is matched against by the branch-and-bound and Ceres matchers: a dense grid of
// M(x) in [0, 1], the "occupancy probability" of seed 001 §2.2 (argmin_T Σ (1 − M(S_i(T)))²).
// A map_server map is binary, so M is made smooth by a Gaussian of the distance to the nearest
// occupied cell, M = exp(−d² / 2σ²): a return on a wall scores 1, one σ away 0.61, and the
// Ceres refinement gets a gradient within a few σ of the walls.
namespace semchain::mapping {

struct MatchGridOptions {
  double sigma_meters = 0.05;  // width of the Gaussian around occupied cells
  // M of cells the map does not know (never observed, or outside it): 0 scores a return
  // there as a miss, so a search prefers poses that put more of the scan on the known map; a
  // value u makes such returns count as u, neither evidence for nor against a pose whose known
  // returns score u. Returns on known free cells stay misses.
  double unknown_value = 0.0;

  bool Validate(std::string* error) const;
};

struct MatchGrid {
  int width = 0;
  int height = 0;
  double resolution = 0.05;
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // lower-left corner of cell (0, 0)
  std::vector<float> values;                         // row-major, row 0 at y = origin.y
  float outside = 0.0f;  // M outside the grid (MatchGridOptions::unknown_value)

  // M of a cell; 'outside' outside the grid (nothing is known to be there).
  float At(int x, int y) const {
    if (x < 0 || y < 0 || x >= width || y >= height) return outside;
    return values[static_cast<std::size_t>(y * width + x)];
  }
  // Continuous cell coordinates of 'world' (cell (i, j) spans [i, i+1) × [j, j+1)).
  Eigen::Vector2d ToGrid(const Eigen::Vector2d& world) const {
    return (world - origin) / resolution;
  }
  // The cell 'world' falls in (possibly outside the grid).
  Eigen::Vector2i CellOf(const Eigen::Vector2d& world) const {
    const Eigen::Vector2d g = ToGrid(world);
    return {static_cast<int>(std::floor(g.x())), static_cast<int>(std::floor(g.y()))};
  }
  Eigen::Vector2d Center() const {
    return origin + 0.5 * resolution * Eigen::Vector2d(width, height);
  }
};

// M for 'map' (occupied cells as map_server thresholds them).
MatchGrid MakeMatchGrid(const MapImage& map, const MatchGridOptions& options = {});

// Mean M over 'points' (robot frame, metres) placed at 'pose', each read in the cell it falls
// in: the score the branch-and-bound search gives a pose, a few nanoseconds a point (the
// bicubic MatchScore of the Ceres refinement costs far more). 0 without points.
double CellScore(const MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                 const Pose2& pose);

// CellScore, or -1 as soon as even every remaining point scoring M = 1 could not lift the mean
// to 'at_least': where it returns a score, the same value as CellScore, and a pose far off is
// dropped after part of its points (the match covariance scores a window of ~10⁵ poses).
double CellScoreIfAtLeast(const MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                          const Pose2& pose, double at_least);

}  // namespace semchain::mapping
