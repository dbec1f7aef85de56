#include "mapping/match_covariance.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"

namespace semchain::mapping {

bool MatchCovarianceOptions::Validate(std::string* error) const {
  if (!(window_meters > 0.0 && window_radians >= 0.0 && linear_step_meters > 0.0 &&
        angular_step_radians > 0.0)) {
    *error = "match covariance: windows and steps must be positive";
    return false;
  }
  if (window_meters / linear_step_meters > 200.0 || window_radians / angular_step_radians > 50.0) {
    *error = "match covariance: at most 200 linear and 50 angular steps each way";
    return false;
  }
  if (!(score_drop > 0.0 && score_drop <= 1.0)) {
    *error = "match covariance: score_drop must be in (0, 1]";
    return false;
  }
  return true;
}

namespace {

// CellScore of 'points' at 'pose', or -1 as soon as even every remaining point scoring the
// grid's maximum (M = 1) could not lift it to 'at_least': where it returns a score, the same
// value as CellScore, and most poses of a wide window are dropped after part of their points.
double ScoreIfAtLeast(const MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                      const Pose2& pose, double at_least) {
  if (points.empty()) return 0.0;
  const Eigen::Isometry2d transform = pose.ToIsometry();
  const double count = static_cast<double>(points.size());
  // A hair below the bound, so that rounding never drops a pose CellScore would keep.
  const double needed = at_least * count - 1e-9 * count;
  double sum = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Eigen::Vector2i cell = grid.CellOf(transform * points[k]);
    sum += grid.At(cell.x(), cell.y());
    if (sum + static_cast<double>(points.size() - k - 1) < needed) return -1.0;
  }
  return sum / count;
}

}  // namespace

Eigen::Matrix3d MatchCovariance(const MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                                const Pose2& match, const MatchCovarianceOptions& options) {
  std::string error;
  SEMCHAIN_CHECK(options.Validate(&error));
  const int linear =
      static_cast<int>(std::floor(options.window_meters / options.linear_step_meters));
  const int angular =
      static_cast<int>(std::floor(options.window_radians / options.angular_step_radians));
  const double best = CellScore(grid, points, match);
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  double weights = 0.0;
  std::vector<Eigen::Vector2d> turned(points.size());
  for (int a = -angular; a <= angular; ++a) {
    const double dtheta = a * options.angular_step_radians;
    // The points turned once per angle; each translation then only shifts them.
    const Pose2 rotation(0.0, 0.0, match.theta + dtheta);
    for (std::size_t k = 0; k < points.size(); ++k) turned[k] = rotation * points[k];
    for (int iy = -linear; iy <= linear; ++iy) {
      for (int ix = -linear; ix <= linear; ++ix) {
        const Eigen::Vector3d offset(ix * options.linear_step_meters,
                                     iy * options.linear_step_meters, dtheta);
        const double score =
            ScoreIfAtLeast(grid, turned, Pose2(match.x + offset.x(), match.y + offset.y(), 0.0),
                           best - options.score_drop);
        if (score < best - options.score_drop) continue;
        sum += score * offset * offset.transpose();
        weights += score;
      }
    }
  }
  // The match itself always counts, so weights > 0 whenever it scores at all.
  Eigen::Matrix3d covariance =
      weights > 0.0 ? Eigen::Matrix3d(sum / weights) : Eigen::Matrix3d::Zero();
  const double linear_floor = options.linear_step_meters * options.linear_step_meters / 12.0;
  const double angular_floor = options.angular_step_radians * options.angular_step_radians / 12.0;
  covariance(0, 0) += linear_floor;
  covariance(1, 1) += linear_floor;
  covariance(2, 2) += angular_floor;
  return covariance;
}

}  // namespace semchain::mapping
