#include "eval/track_benchmark.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"
#include "core/check.h"
#include "core/cpu_time.h"

namespace semchain::eval {

std::vector<TrackedScan> TrackScans(const localization::LocalizerMap& map,
                                    localization::LocalizationMethod method,
                                    const std::vector<StampedScan>& scans,
                                    const std::vector<Pose2>& reference,
                                    const TrackOptions& options) {
  SEMCHAIN_CHECK(!scans.empty() && reference.size() == scans.size());
  localization::Localizer localizer(map, method, options.localizer);
  const Eigen::Vector3d sigmas(options.initial_sigma_meters, options.initial_sigma_meters,
                               options.initial_sigma_radians);
  // Applied at the first scan's odometry, where the reference's first pose is.
  localizer.SetInitialPose(reference.front(), sigmas.cwiseAbs2().asDiagonal());
  std::vector<TrackedScan> track;
  track.reserve(scans.size());
  for (std::size_t i = 0; i < scans.size(); ++i) {
    TrackedScan t;
    t.stamp = scans[i].scan.timestamp;
    const double start = ThreadCpuSeconds();
    const localization::LocalizerStatistics before = localizer.statistics();
    const int filter_updates = localizer.AddScan(scans[i]);
    t.cpu_ms = 1000.0 * (ThreadCpuSeconds() - start);
    const localization::LocalizerStatistics& after = localizer.statistics();
    t.updates = filter_updates + after.scan_match_tries - before.scan_match_tries;
    t.scan_matched = after.scan_matches > before.scan_matches;
    if (localizer.pose()) {
      t.estimated = true;
      t.estimate = *localizer.pose();
      t.error_m = (t.estimate.translation() - reference[i].translation()).norm();
      t.error_deg = std::abs(RadToDeg(AngleDifference(t.estimate.theta, reference[i].theta)));
      t.score = mapping::CellScore(
          map.matcher.grid(),
          map.matcher.MatchPoints(scans[i].scan, scans[i].LaserOffset(),
                                  options.localizer.scan_tracking.point_spacing_meters),
          t.estimate);
    }
    track.push_back(t);
  }
  return track;
}

TrackSummary SummarizeTrack(const std::vector<TrackedScan>& track) {
  TrackSummary s;
  s.scans = static_cast<int>(track.size());
  std::vector<double> meters, degrees;
  double update_cpu = 0.0, all_cpu = 0.0;
  for (const TrackedScan& t : track) {
    all_cpu += t.cpu_ms;
    s.updates += t.updates;
    if (t.scan_matched) ++s.scan_matched;
    if (t.updates > 0) update_cpu += t.cpu_ms;
    if (!t.estimated) continue;
    ++s.estimated;
    meters.push_back(t.error_m);
    degrees.push_back(t.error_deg);
  }
  s.median_m = Percentile(meters, 50.0);
  s.p95_m = Percentile(meters, 95.0);
  s.max_m = Percentile(meters, 100.0);
  s.median_deg = Percentile(degrees, 50.0);
  s.p95_deg = Percentile(degrees, 95.0);
  s.max_deg = Percentile(degrees, 100.0);
  s.cpu_ms_per_update = s.updates > 0 ? update_cpu / s.updates : 0.0;
  s.cpu_ms_per_scan = s.scans > 0 ? all_cpu / s.scans : 0.0;
  return s;
}

}  // namespace semchain::eval
