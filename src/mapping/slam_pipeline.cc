#include "mapping/slam_pipeline.h"

#include <utility>

#include "core/check.h"

namespace semchain::mapping {
Result<std::vector<StampedScan>> ScansFromLog(const carmen::Log& log, const std::string& source,
                                              ReversedOdometryRepair* repair) {
  if (log.records.empty()) return Status::Error(source + ": empty log (no records)");
  std::vector<StampedScan> scans;
  // Each scan keeps its own geometry: an interlaced laser (fr-clinic) cycles its start angle
  // and beam count from scan to scan.
  for (const carmen::Laser* laser : log.Lasers()) {
    if (laser->scan.scan.size() == 0) {
      return Status::Error(source + ": laser scan " + std::to_string(scans.size() + 1) +
                           " has no beams");
    }
    scans.push_back(laser->scan);
  }
  if (scans.empty()) {
    return Status::Error(source + ": no laser scans (FLASER or ROBOTLASER1 lines) in the log");
  }
  if (repair != nullptr) *repair = RepairReversedOdometry(log.Odometries(), &scans);
  return scans;
}

SlamResult RunSlam(const std::vector<StampedScan>& scans, const SlamOptions& options,
                   const std::function<void(std::size_t)>& progress,
                   const std::function<void(const SlamStep&)>& observe) {
  SEMCHAIN_CHECK(!scans.empty());
  IncrementalSlam slam(options);
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const SlamStep step = slam.AddScan(scans[i]);
    if (observe) observe(step);
    if (progress) progress(i + 1);
  }
  return std::move(slam).Finish(progress);
}

}  // namespace semchain::mapping
