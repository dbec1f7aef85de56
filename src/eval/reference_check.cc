#include "eval/reference_check.h"

#include <cmath>

#include "core/angles.h"
#include "core/check.h"

namespace semchain::eval {

std::vector<ReferenceCheck> CheckReference(const localization::ScanMatchRelocalizer& matcher,
                                           const std::vector<StampedScan>& scans,
                                           const std::vector<Pose2>& reference,
                                           double point_spacing_meters) {
  SEMCHAIN_CHECK(reference.size() == scans.size());
  std::vector<ReferenceCheck> checks(scans.size());
  for (std::size_t i = 0; i < scans.size(); ++i) {
    ReferenceCheck& c = checks[i];
    if (i > 0) {
      const Pose2 moved = reference[i - 1].Between(reference[i]);
      const Pose2 odometry = scans[i - 1].odometry.Between(scans[i].odometry);
      const Pose2 residual = odometry.Between(moved);
      c.motion_m = residual.translation().norm();
      c.motion_deg = std::abs(RadToDeg(residual.theta));
    }
    const std::vector<Eigen::Vector2d> points =
        matcher.MatchPoints(scans[i].scan, scans[i].LaserOffset(), point_spacing_meters);
    c.points = static_cast<int>(points.size());
    if (points.empty()) continue;
    c.score = mapping::CellScore(matcher.grid(), points, reference[i]);
    const Pose2 fit = matcher.Refine(points, reference[i]);
    c.fit_m = (fit.translation() - reference[i].translation()).norm();
    c.fit_deg = std::abs(RadToDeg(AngleDifference(fit.theta, reference[i].theta)));
  }
  return checks;
}

}  // namespace semchain::eval
