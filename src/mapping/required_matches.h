#pragma once

#include <algorithm>
#include <cmath>

// How many of a scan's returns a scan match must put on obstacles to be trusted. The counts the
// options give (laser odometry 60, the proposal 30, every-scan localization 50) suit a lidar
// whose beams mostly return (180 or 361 of them); a Neato's 361 beams return 20 to 150 times
// (70 % of its readings are 0), so against fixed counts its matches are rejected outright: the
// laser odometry falls back to the wheel odometry, the filter to the motion model and the
// every-scan pass keeps interpolated poses, and the map's trajectory follows a wheel odometry
// whose scans are stamped 0.2–0.4 s late (10–20° off in turns). The count is relative to the
// readings that measured something (PreparedScan::measured), not to the returns within match
// range: a scan in open space (the Freiburg campus) measured far walls and empty directions with
// all its beams, and its few near returns must still match the full count. Relative to the
// near returns, such scans' matches were trusted on a third of them, and the filter drifted:
// the Freiburg campus with the pose graph went from 1.17 to 14.0 m ATE (docs/experiments.md).
namespace semchain::mapping {

// Scans with fewer than 3 × 'min_matched' points to count over need a third of them.
inline constexpr double kRequiredMatchFraction = 1.0 / 3.0;

// The matched count required of a match counted over 'available' measured readings: 'min_matched',
// or a third of 'available' when that is fewer, but at least one (a scan without returns matches
// nothing); 'min_matched' 0 requires nothing.
inline int RequiredMatches(int min_matched, int available) {
  if (min_matched <= 0) return min_matched;
  const int fraction =
      static_cast<int>(std::ceil(kRequiredMatchFraction * static_cast<double>(available)));
  return std::max(1, std::min(min_matched, fraction));
}

}  // namespace semchain::mapping
