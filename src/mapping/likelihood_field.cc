#include "mapping/likelihood_field.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.h"

namespace semchain::mapping {
namespace {

// Squared distance from 'p' to the line through a and b, when a and b are neighbouring
// obstacle means of one surface (0.3 to 2 cells apart) and 'p' projects near them (within one
// segment length beyond either end); else +inf. The line, not the segment: an endpoint between
// two sparse earlier endpoints must not be pulled along the wall towards either.
double LineDistanceSquared(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                           const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length_squared = ab.squaredNorm();
  if (length_squared < 0.09 || length_squared > 4.0) {
    return std::numeric_limits<double>::infinity();
  }
  const double t = (p - a).dot(ab) / length_squared;
  if (t < -1.0 || t > 2.0) return std::numeric_limits<double>::infinity();
  return (a + t * ab - p).squaredNorm();
}

}  // namespace

bool LikelihoodFieldOptions::Validate(std::string* error) const {
  if (kernel_cells < 0 || kernel_cells > 5) {
    *error = "kernel_cells must be in [0, 5]";
    return false;
  }
  if (!(score_sigma_meters > 0.0 && likelihood_sigma_meters > 0.0)) {
    *error = "score_sigma_meters and likelihood_sigma_meters must be positive";
    return false;
  }
  if (!(max_distance_meters > 0.0)) {
    *error = "max_distance_meters must be positive";
    return false;
  }
  return true;
}

LikelihoodField::LikelihoodField(const OccupancyGrid& grid, const LikelihoodFieldOptions& options)
    : grid_(grid),
      options_(options),
      obstacle_(static_cast<float>(options.obstacle_log_odds)),
      score_factor_(-0.5 / (options.score_sigma_meters * options.score_sigma_meters)),
      likelihood_factor_(-0.5 /
                         (options.likelihood_sigma_meters * options.likelihood_sigma_meters)),
      max_distance_squared_(options.max_distance_meters * options.max_distance_meters),
      inverse_resolution_(1.0 / grid.resolution()),
      max_cells_squared_(max_distance_squared_ * inverse_resolution_ * inverse_resolution_) {
  std::string error;
  SEMCHAIN_CHECK(options_.Validate(&error));
}

LikelihoodField::Nearest LikelihoodField::FindNearest(const Eigen::Vector2d& g,
                                                      const Eigen::Vector2d& direction) const {
  const int k = options_.kernel_cells;
  const GridCell* block[121];
  const GridCell* front_block[121];
  const Eigen::Vector2i cell(static_cast<int>(std::floor(g.x())),
                             static_cast<int>(std::floor(g.y())));
  grid_.FetchBlock(cell, k, block);
  if (options_.require_free_in_front) {
    // One step back towards the sensor, exactly one cell along the dominant axis, so that the
    // "front" cell is never the endpoint's own.
    const Eigen::Vector2d f = g - direction / direction.cwiseAbs().maxCoeff();
    grid_.FetchBlock({static_cast<int>(std::floor(f.x())), static_cast<int>(std::floor(f.y()))}, k,
                     front_block);
  }
  // The two nearest obstacle means: the surface runs between them when they are neighbours.
  Nearest nearest;
  double best = max_cells_squared_, second = max_cells_squared_;
  Eigen::Vector2d second_mean = Eigen::Vector2d::Zero();
  for (int dy = -k, b = 0; dy <= k; ++dy) {
    for (int dx = -k; dx <= k; ++dx, ++b) {
      const GridCell* obstacle = block[b];
      if (obstacle == nullptr || obstacle->log_odds <= obstacle_) continue;
      if (options_.require_free_in_front && front_block[b] != nullptr &&
          front_block[b]->log_odds > obstacle_) {
        continue;
      }
      nearest.found = true;
      const Eigen::Vector2d mean(cell.x() + dx + 0.5 + obstacle->mean_x * inverse_resolution_,
                                 cell.y() + dy + 0.5 + obstacle->mean_y * inverse_resolution_);
      const double distance_squared = (g - mean).squaredNorm();
      if (distance_squared < best) {
        second = best;
        second_mean = nearest.anchor;
        best = distance_squared;
        nearest.anchor = mean;
      } else if (distance_squared < second) {
        second = distance_squared;
        second_mean = mean;
      }
    }
  }
  nearest.distance_squared = best;
  if (!nearest.found) return nearest;
  const Eigen::Vector2d offset = g - nearest.anchor;
  nearest.normal = offset.norm() > 1e-9 ? Eigen::Vector2d(offset.normalized()) : -direction;
  if (options_.interpolate_surface && second < max_cells_squared_) {
    const double along = LineDistanceSquared(g, nearest.anchor, second_mean);
    if (along < nearest.distance_squared) {
      nearest.distance_squared = along;
      nearest.on_line = true;
      const Eigen::Vector2d tangent = (second_mean - nearest.anchor).normalized();
      nearest.normal = Eigen::Vector2d(-tangent.y(), tangent.x());
    }
  }
  return nearest;
}

FieldEvaluation LikelihoodField::Evaluate(const MatchPoints& points, const Pose2& pose) const {
  FieldEvaluation result;
  const double c = std::cos(pose.theta);
  const double s = std::sin(pose.theta);
  const Eigen::Vector2d origin = grid_.origin();
  // Work in grid units (cells); squared distances are scaled back to metres².
  const double cell_squared = grid_.resolution() * grid_.resolution();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d& p = points.points[i];
    const Eigen::Vector2d& d = points.directions[i];
    const Eigen::Vector2d g((pose.x + c * p.x() - s * p.y() - origin.x()) * inverse_resolution_,
                            (pose.y + s * p.x() + c * p.y() - origin.y()) * inverse_resolution_);
    const Nearest nearest =
        FindNearest(g, Eigen::Vector2d(c * d.x() - s * d.y(), s * d.x() + c * d.y()));
    const double best = nearest.distance_squared * cell_squared;
    if (nearest.found) {
      ++result.matched;
      result.score += std::exp(score_factor_ * best);
    }
    result.log_likelihood += likelihood_factor_ * best;
  }
  return result;
}

}  // namespace semchain::mapping
