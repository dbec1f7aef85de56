#include "mapping/prepared_scan.h"

#include <algorithm>
#include <cmath>

namespace semchain::mapping {

bool ScanPreparationOptions::Validate(std::string* error) const {
  if (!(min_range_meters >= 0.0)) {
    *error = "min_range_meters must be >= 0";
    return false;
  }
  if (!(max_range_meters > min_range_meters)) {
    *error = "max_range_meters must be greater than min_range_meters";
    return false;
  }
  if (!(no_return_clear_meters >= 0.0)) {
    *error = "no_return_clear_meters must be >= 0";
    return false;
  }
  return true;
}

int PreparedScan::HitCount() const {
  return static_cast<int>(
      std::count_if(beams.begin(), beams.end(), [](const PreparedBeam& b) { return b.hit; }));
}

PreparedScan PrepareScan(const LaserScan& scan, const Pose2& laser_offset,
                         const ScanPreparationOptions& options) {
  PreparedScan prepared;
  prepared.timestamp = scan.timestamp;
  prepared.sensor_origin = laser_offset.translation();
  prepared.beams.reserve(scan.size());
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const double angle = laser_offset.theta + scan.BeamAngle(i);
    const Eigen::Vector2d direction(std::cos(angle), std::sin(angle));
    const double range = scan.ranges[i];
    if (range >= options.min_range_meters) ++prepared.measured;
    double length = 0.0;
    bool hit = false;
    if (scan.IsReturn(i) && range >= options.min_range_meters) {
      hit = range <= options.max_range_meters;
      length = std::min(range, options.max_range_meters);
    } else if (options.no_return_clear_meters > 0.0 && !(range > 0.0 && range < scan.max_range)) {
      length = std::min(options.no_return_clear_meters, options.max_range_meters);
    } else {
      continue;
    }
    prepared.beams.push_back({prepared.sensor_origin + length * direction, direction, hit});
  }
  return prepared;
}

MatchPoints SelectMatchPoints(const PreparedScan& scan, double max_range_meters, int beam_step) {
  MatchPoints points;
  const double max_squared = max_range_meters * max_range_meters;
  const int step = std::max(1, beam_step);
  int index = 0;
  for (const PreparedBeam& beam : scan.beams) {
    if (!beam.hit) continue;
    if ((beam.endpoint - scan.sensor_origin).squaredNorm() > max_squared) continue;
    if (index++ % step != 0) continue;
    points.points.push_back(beam.endpoint);
    points.directions.push_back(beam.direction);
  }
  points.measured = std::max((scan.measured + step - 1) / step, static_cast<int>(points.size()));
  return points;
}

}  // namespace semchain::mapping
