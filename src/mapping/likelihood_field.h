#pragma once

#include <string>

#include "core/pose2.h"
#include "mapping/occupancy_grid.h"
#include "mapping/prepared_scan.h"

// The likelihood field of a scan on an occupancy grid (Thrun et al., Probabilistic Robotics
// §6.4), evaluated lazily so that it works on maps that change every step: each beam endpoint
// is compared with the nearest obstacle within a small kernel, where an obstacle's position is
// the mean of the endpoints that built it (sub-cell accuracy), and an obstacle only counts when
// the cell in front of it along the beam is not an obstacle too (the beam must reach it from
// free space, which keeps scans from locking onto the back of walls).
namespace semchain::mapping {

struct LikelihoodFieldOptions {
  // Obstacles are searched in the (2k+1)² cells around each endpoint (GMapping kernelSize).
  int kernel_cells = 1;
  // A cell is an obstacle when its log-odds exceed this (0 = P > 0.5).
  double obstacle_log_odds = 0.0;
  bool require_free_in_front = true;
  // Distance to the line through the two nearest obstacle means (when neighbours) instead of
  // to the nearest mean: removes the error, and the pull, along walls.
  bool interpolate_surface = true;
  // Matching score: Σ exp(-d² / (2 σ²)) over endpoints at distance d from their obstacle.
  double score_sigma_meters = 0.05;
  // Observation log-likelihood: Σ max(-d² / (2 σ²), -d_max² / (2 σ²)); an endpoint without an
  // obstacle in the kernel counts as d = d_max.
  // (GMapping's lsigma is 0.075, but its likelihood is then tempered; we keep the measurement
  // scale here and temper the particle weights instead, RbpfOptions::weight_gain.)
  double likelihood_sigma_meters = 0.03;
  double max_distance_meters = 0.15;

  bool Validate(std::string* error) const;
};

struct FieldEvaluation {
  double score = 0.0;           // the hill climber's objective
  double log_likelihood = 0.0;  // log p(z | m, x), up to a constant
  int matched = 0;              // endpoints with an obstacle in their kernel
};

class LikelihoodField {
 public:
  // 'grid' must outlive this object.
  LikelihoodField(const OccupancyGrid& grid, const LikelihoodFieldOptions& options);

  // Scores 'points' (robot frame) placed at robot pose 'pose'.
  FieldEvaluation Evaluate(const MatchPoints& points, const Pose2& pose) const;

  // The surface nearest to a beam endpoint, in grid units (cells) relative to the grid origin.
  struct Nearest {
    bool found = false;           // an obstacle in the kernel
    double distance_squared = 0;  // to the surface, capped at max_distance (cells²)
    Eigen::Vector2d anchor = Eigen::Vector2d::Zero();  // the nearest obstacle mean
    Eigen::Vector2d normal = Eigen::Vector2d::Zero();  // unit; the residual is normal·(p - anchor)
    bool on_line = false;  // the normal is that of a line through two obstacle means
  };
  // 'g' is the endpoint and 'direction' the beam's unit direction, both in the world frame
  // ('g' in grid units).
  Nearest FindNearest(const Eigen::Vector2d& g, const Eigen::Vector2d& direction) const;
  double inverse_resolution() const { return inverse_resolution_; }

  const OccupancyGrid& grid() const { return grid_; }
  const LikelihoodFieldOptions& options() const { return options_; }

 private:
  const OccupancyGrid& grid_;
  LikelihoodFieldOptions options_;
  float obstacle_;
  double score_factor_;       // -1 / (2 σ_s²)
  double likelihood_factor_;  // -1 / (2 σ_l²)
  double max_distance_squared_;
  double inverse_resolution_;
  double max_cells_squared_;
};

}  // namespace semchain::mapping
