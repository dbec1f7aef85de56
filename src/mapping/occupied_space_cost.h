#pragma once

#include <ceres/cubic_interpolation.h>

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "mapping/match_grid.h"

// The residuals of seed 001 §2.2, r_i = 1 − M(S_i(T)) (Cartographer's occupied-space cost):
// S_i(T) is return i moved by the pose T = (x, y, θ), M the match grid read with bicubic
// interpolation (ceres::BiCubicInterpolator), which is smooth enough for automatic
// differentiation. Each residual is scaled by weight / sqrt(N) so that the cost does not grow
// with the number of returns.
namespace semchain::mapping {

class OccupiedSpaceCost {
 public:
  using Grid = ceres::Grid2D<float, 1>;

  // 'grid' and 'points' (robot frame, metres) must outlive this functor.
  OccupiedSpaceCost(const MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                    double weight)
      : grid_(grid),
        points_(points),
        scale_(weight / std::sqrt(static_cast<double>(points.size()))),
        // Rows are y, columns x; outside the grid Grid2D repeats the border, which is free
        // space (M ≈ 0) in a map with a margin.
        adapter_(grid.values.data(), 0, grid.height, 0, grid.width),
        interpolator_(adapter_) {}

  template <typename T>
  bool operator()(const T* const pose, T* residuals) const {
    using std::cos;
    using std::sin;
    const T c = cos(pose[2]);
    const T s = sin(pose[2]);
    const double inverse = 1.0 / grid_.resolution;
    for (std::size_t i = 0; i < points_.size(); ++i) {
      const Eigen::Vector2d& p = points_[i];
      const T wx = pose[0] + c * p.x() - s * p.y();
      const T wy = pose[1] + s * p.x() + c * p.y();
      // Grid values sit at cell centres: cell (i, j) is sample (row j, column i).
      const T column = (wx - grid_.origin.x()) * inverse - 0.5;
      const T row = (wy - grid_.origin.y()) * inverse - 0.5;
      T m;
      interpolator_.Evaluate(row, column, &m);
      residuals[i] = scale_ * (1.0 - m);
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

// Pulls the pose towards 'target' (Cartographer's translation and rotation delta costs): three
// residuals weight × (x − x₀), weight × (y − y₀), weight × (θ − θ₀).
class PoseDeltaCost {
 public:
  PoseDeltaCost(const Eigen::Vector3d& target, double translation_weight, double rotation_weight)
      : target_(target),
        translation_weight_(translation_weight),
        rotation_weight_(rotation_weight) {}

  template <typename T>
  bool operator()(const T* const pose, T* residuals) const {
    residuals[0] = translation_weight_ * (pose[0] - target_.x());
    residuals[1] = translation_weight_ * (pose[1] - target_.y());
    residuals[2] = rotation_weight_ * (pose[2] - target_.z());
    return true;
  }

 private:
  Eigen::Vector3d target_;
  double translation_weight_;
  double rotation_weight_;
};

}  // namespace semchain::mapping
