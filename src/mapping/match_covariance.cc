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
            CellScoreIfAtLeast(grid, turned, Pose2(match.x + offset.x(), match.y + offset.y(), 0.0),
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
