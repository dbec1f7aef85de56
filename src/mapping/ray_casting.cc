#include "mapping/ray_casting.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace semchain::mapping {

void TraceSegmentCells(const Eigen::Vector2d& start, const Eigen::Vector2d& end,
                       std::vector<Eigen::Vector2i>* cells) {
  Eigen::Vector2i cell(static_cast<int>(std::floor(start.x())),
                       static_cast<int>(std::floor(start.y())));
  const Eigen::Vector2i last(static_cast<int>(std::floor(end.x())),
                             static_cast<int>(std::floor(end.y())));
  const Eigen::Vector2d delta = end - start;
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  int step[2];
  double t_max[2];
  double t_delta[2];
  for (int k = 0; k < 2; ++k) {
    step[k] = delta[k] > 0.0 ? 1 : (delta[k] < 0.0 ? -1 : 0);
    if (step[k] == 0) {
      t_max[k] = kInfinity;
      t_delta[k] = kInfinity;
      continue;
    }
    const double boundary = step[k] > 0 ? cell[k] + 1.0 : static_cast<double>(cell[k]);
    t_max[k] = (boundary - start[k]) / delta[k];
    t_delta[k] = std::abs(1.0 / delta[k]);
  }
  // At most |Δi| + |Δj| steps; the bound also guards against rounding at exact corners.
  const int max_steps = std::abs(last.x() - cell.x()) + std::abs(last.y() - cell.y());
  for (int i = 0; i < max_steps && cell != last; ++i) {
    cells->push_back(cell);
    const int k = t_max[0] < t_max[1] ? 0 : 1;
    cell[k] += step[k];
    t_max[k] += t_delta[k];
  }
}

bool ScanInserter::Mark(const Eigen::Vector2i& cell) {
  const Eigen::Vector2i local = cell - box_min_;
  std::uint32_t& stamp = stamps_[static_cast<std::size_t>(local.y() * box_width_ + local.x())];
  if (stamp == generation_) return false;
  stamp = generation_;
  return true;
}

void ScanInserter::Insert(const PreparedScan& scan, const Pose2& pose, OccupancyGrid* grid) {
  const double inverse_resolution = 1.0 / grid->resolution();
  const Eigen::Isometry2d transform = pose.ToIsometry();
  const Eigen::Vector2d sensor_world = transform * scan.sensor_origin;
  // Grid coordinates (cell units) of the sensor and of every endpoint.
  auto to_grid = [&](const Eigen::Vector2d& world) -> Eigen::Vector2d {
    return (world - grid->origin()) * inverse_resolution;
  };
  const Eigen::Vector2d sensor = to_grid(sensor_world);
  Eigen::Vector2d lo = sensor, hi = sensor;
  std::vector<Eigen::Vector2d> ends(scan.beams.size());
  for (std::size_t i = 0; i < scan.beams.size(); ++i) {
    ends[i] = to_grid(transform * scan.beams[i].endpoint);
    lo = lo.cwiseMin(ends[i]);
    hi = hi.cwiseMax(ends[i]);
  }
  box_min_ = Eigen::Vector2i(static_cast<int>(std::floor(lo.x())) - 1,
                             static_cast<int>(std::floor(lo.y())) - 1);
  box_width_ = static_cast<int>(std::floor(hi.x())) + 2 - box_min_.x();
  const int box_height = static_cast<int>(std::floor(hi.y())) + 2 - box_min_.y();
  const std::size_t needed = static_cast<std::size_t>(box_width_) * box_height;
  if (stamps_.size() < needed) stamps_.assign(needed, 0);
  if (++generation_ == 0) {  // wrapped: forget every old stamp
    std::fill(stamps_.begin(), stamps_.end(), 0);
    generation_ = 1;
  }
  for (std::size_t i = 0; i < scan.beams.size(); ++i) {
    if (!scan.beams[i].hit) continue;
    const Eigen::Vector2i cell(static_cast<int>(std::floor(ends[i].x())),
                               static_cast<int>(std::floor(ends[i].y())));
    if (Mark(cell)) grid->AddHit(cell, transform * scan.beams[i].endpoint);
  }
  for (std::size_t i = 0; i < scan.beams.size(); ++i) {
    ray_.clear();
    TraceSegmentCells(sensor, ends[i], &ray_);
    for (const Eigen::Vector2i& cell : ray_) {
      if (Mark(cell)) grid->AddMiss(cell);
    }
    if (!scan.beams[i].hit) {  // a free-space-only beam frees its last cell too
      const Eigen::Vector2i cell(static_cast<int>(std::floor(ends[i].x())),
                                 static_cast<int>(std::floor(ends[i].y())));
      if (Mark(cell)) grid->AddMiss(cell);
    }
  }
}

void InsertScan(const PreparedScan& scan, const Pose2& pose, OccupancyGrid* grid) {
  thread_local ScanInserter inserter;
  inserter.Insert(scan, pose, grid);
}

}  // namespace semchain::mapping
