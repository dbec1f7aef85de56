#include "mapping/slam_pipeline.h"

#include "core/check.h"

namespace semchain::mapping {
Result<std::vector<StampedScan>> ScansFromLog(const carmen::Log& log, const std::string& source,
                                              ReversedOdometryRepair* repair) {
  if (log.records.empty()) return Status::Error(source + ": empty log (no records)");
  std::vector<StampedScan> scans;
  for (const carmen::Laser* laser : log.Lasers()) {
    if (!scans.empty() && laser->scan.scan.size() != scans.front().scan.size()) {
      return Status::Error(source + ": laser scan " + std::to_string(scans.size() + 1) + " has " +
                           std::to_string(laser->scan.scan.size()) + " beams, the first has " +
                           std::to_string(scans.front().scan.size()) +
                           " (inconsistent beam counts)");
    }
    scans.push_back(laser->scan);
  }
  if (scans.empty()) {
    return Status::Error(source + ": no laser scans (FLASER or ROBOTLASER1 lines) in the log");
  }
  if (scans.front().scan.size() == 0) return Status::Error(source + ": laser scans have no beams");
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
  return slam.Finish(progress);
}

}  // namespace semchain::mapping
