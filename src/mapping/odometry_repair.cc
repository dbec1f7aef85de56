#include "mapping/odometry_repair.h"

#include <algorithm>
#include <cmath>

namespace semchain::mapping {
namespace {

// The translational velocity of the record nearest to 'time' ('records' sorted by time).
double VelocityAt(const std::vector<const carmen::Odometry*>& records, double time) {
  const auto after = std::lower_bound(
      records.begin(), records.end(), time,
      [](const carmen::Odometry* record, double t) { return record->stamp.timestamp < t; });
  if (after == records.end()) return records.back()->tv;
  if (after == records.begin()) return (*after)->tv;
  const auto before = std::prev(after);
  return time - (*before)->stamp.timestamp <= (*after)->stamp.timestamp - time ? (*before)->tv
                                                                               : (*after)->tv;
}

}  // namespace

ReversedOdometryRepair RepairReversedOdometry(const std::vector<const carmen::Odometry*>& records,
                                              std::vector<StampedScan>* scans, double min_speed) {
  ReversedOdometryRepair repair;
  if (records.empty() || scans->size() < 2) return repair;
  std::vector<const carmen::Odometry*> sorted = records;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const carmen::Odometry* a, const carmen::Odometry* b) {
                     return a->stamp.timestamp < b->stamp.timestamp;
                   });
  Pose2 previous_logged = scans->front().odometry;
  bool rechain = false;  // from the first reversed step on (before it the log stays as written)
  for (std::size_t i = 1; i < scans->size(); ++i) {
    StampedScan& scan = (*scans)[i];
    const Pose2 logged = scan.odometry;
    const Pose2 laser_offset = scan.LaserOffset();
    Pose2 step = previous_logged.Between(logged);
    const double middle = 0.5 * ((*scans)[i - 1].scan.timestamp + scan.scan.timestamp);
    if (step.x > 0.0 && VelocityAt(sorted, middle) < -min_speed) {
      step = Pose2(-step.x, -step.y, step.theta);
      ++repair.steps;
      repair.meters += std::hypot(step.x, step.y);
      rechain = true;
    }
    previous_logged = logged;
    if (rechain) {
      scan.odometry = (*scans)[i - 1].odometry * step;
      scan.laser_pose = scan.odometry * laser_offset;
    }
  }
  return repair;
}

}  // namespace semchain::mapping
