#pragma once

#include <vector>

#include "core/pose2.h"
#include "localization/scan_match_relocalizer.h"
#include "sensors/laser_scan.h"

// How far a map's own trajectory can be trusted as the reference of a tracking run
// (`semchain bench track`): for each scan, how its reference pose moves against the odometry
// and how far the scan, placed at that pose, is from where it fits the map best. A tracker that
// follows the map's best fit cannot come closer to the reference than the second; a reference
// that jumps where the odometry does not shows in the first.
namespace semchain::eval {

struct ReferenceCheck {
  // |(r_{i−1}⁻¹ r_i) ⊖ (o_{i−1}⁻¹ o_i)|: the reference's motion from the previous scan against
  // the odometry's (0 for the first scan).
  double motion_m = 0.0;
  double motion_deg = 0.0;
  // The reference pose against the scan's best fit near it (the scan matcher's Ceres refinement
  // started there); 0 for a scan without returns.
  double fit_m = 0.0;
  double fit_deg = 0.0;
  // The scan matcher's score of the reference pose (mean M of the returns, 0 to 1).
  double score = 0.0;
  int points = 0;  // returns the matcher used
};

// One check per scan; 'reference' has one pose per scan. The returns are thinned to
// 'point_spacing_meters' (as scan tracking thins them).
std::vector<ReferenceCheck> CheckReference(const localization::ScanMatchRelocalizer& matcher,
                                           const std::vector<StampedScan>& scans,
                                           const std::vector<Pose2>& reference,
                                           double point_spacing_meters);

}  // namespace semchain::eval
