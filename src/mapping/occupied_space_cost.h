#pragma once

#include <ceres/cubic_interpolation.h>

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "mapping/match_grid.h"

// The residuals of seed 001 §2.2, r_i = 1 − M(S_i(T)) (Cartographer's occupied-space cost):
// S_i(T) is return i moved by the pose T = (x, y, θ), M the match grid read with bicubic
// interpolation (ceres::BiCubicInterpolator). Each residual is scaled by weight / sqrt(N) so
// that the cost does not grow with the number of returns.
//
// The Jacobian is analytic: the interpolator gives M's gradient with its value, and the chain
// through the rigid motion is three products a point (with automatic differentiation the
// refinement took a few per cent longer on the FR079 benchmark).
namespace semchain::mapping {

class OccupiedSpaceCost {
 public:
  using Grid = ceres::Grid2D<float, 1>;

  // 'grid' and 'points' (robot frame, metres) must outlive this cost.
  OccupiedSpaceCost(const MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                    double weight)
      : grid_(grid),
        points_(points),
        scale_(weight / std::sqrt(static_cast<double>(points.size()))),
        // Rows are y, columns x; outside the grid Grid2D repeats the border, which is free
        // space (M ≈ 0) in a map with a margin.
        adapter_(grid.values.data(), 0, grid.height, 0, grid.width),
        interpolator_(adapter_) {}

  int NumResiduals() const { return static_cast<int>(points_.size()); }

  // The residuals at 'pose' = (x, y, θ) and, unless 'jacobian' is null, their N × 3 Jacobian in
  // column-major order (ceres::TinySolver's layout).
  bool operator()(const double* pose, double* residuals, double* jacobian) const {
    const double c = std::cos(pose[2]);
    const double s = std::sin(pose[2]);
    const double inverse = 1.0 / grid_.resolution;
    const std::size_t n = points_.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector2d& p = points_[i];
      const double rotated_x = c * p.x() - s * p.y();
      const double rotated_y = s * p.x() + c * p.y();
      // Grid values sit at cell centres: cell (i, j) is sample (row j, column i).
      const double column = (pose[0] + rotated_x - grid_.origin.x()) * inverse - 0.5;
      const double row = (pose[1] + rotated_y - grid_.origin.y()) * inverse - 0.5;
      double m = 0.0;
      if (jacobian == nullptr) {
        // The solver asks for the cost alone at each candidate step.
        interpolator_.Evaluate(row, column, &m);
        residuals[i] = scale_ * (1.0 - m);
      } else {
        double dm_drow = 0.0;
        double dm_dcolumn = 0.0;
        interpolator_.Evaluate(row, column, &m, &dm_drow, &dm_dcolumn);
        residuals[i] = scale_ * (1.0 - m);
        // ∂r/∂x = −scale ∂M/∂column / resolution, likewise y; ∂(rotated point)/∂θ =
        // (−rotated_y, rotated_x).
        const double dr_dx = -scale_ * inverse * dm_dcolumn;
        const double dr_dy = -scale_ * inverse * dm_drow;
        jacobian[i] = dr_dx;
        jacobian[n + i] = dr_dy;
        jacobian[2 * n + i] = dr_dy * rotated_x - dr_dx * rotated_y;
      }
    }
    return true;
  }

 private:
  const MatchGrid& grid_;
  const std::vector<Eigen::Vector2d>& points_;
  double scale_;
  Grid adapter_;
  ceres::BiCubicInterpolator<Grid> interpolator_;
};

}  // namespace semchain::mapping
