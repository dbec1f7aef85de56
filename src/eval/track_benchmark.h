#pragma once

#include <optional>
#include <vector>

#include "core/pose2.h"
#include "eval/statistics.h"
#include "localization/localizer.h"
#include "sensors/laser_scan.h"

// Tracking from a known start (`semchain bench track`): a method's Localizer is given the
// reference trajectory's first pose as its initial pose and fed every scan with its odometry in
// time order; after each scan its pose is compared with the reference pose of that scan (the
// trajectory of the map it tracks on, so the error says how well the tracker agrees with the
// map, not with the world).
namespace semchain::eval {

struct TrackOptions {
  // The initial pose's standard deviations (the covariance given with it, as /initialpose).
  double initial_sigma_meters = 0.05;
  double initial_sigma_radians = 0.03;
  // The localizer's options (its seed, scan tracking).
  localization::LocalizerOptions localizer;
};

// One scan of a tracking run.
struct TrackedScan {
  double stamp = 0.0;
  bool estimated = false;  // the method gave a pose after this scan
  Pose2 estimate;
  double error_m = 0.0;    // to the reference pose (estimated scans only)
  double error_deg = 0.0;  // absolute heading error
  // The scan matcher's score of the estimate (mean M of the scan's returns there, 0 to 1; as
  // ReferenceCheck::score scores the reference pose).
  double score = 0.0;
  // Filter updates, matcher runs and scan-tracking matches this scan took.
  int updates = 0;
  bool scan_matched = false;  // scan tracking matched this scan against the map
  double cpu_ms = 0.0;        // CPU of Localizer::AddScan on this scan
};

// Nearest-rank percentile summary of a tracking run's errors and its work.
struct TrackSummary {
  int scans = 0;
  int estimated = 0;     // scans after which the method had a pose
  int updates = 0;       // filter updates, matcher runs and scan-tracking matches in all
  int scan_matched = 0;  // scans scan tracking matched against the map
  double median_m = 0.0, p95_m = 0.0, max_m = 0.0;
  double median_deg = 0.0, p95_deg = 0.0, max_deg = 0.0;
  double cpu_ms_per_update = 0.0;  // CPU of the scans that updated, over the updates
  double cpu_ms_per_scan = 0.0;    // CPU of every scan, over the scans
};

// Tracks 'scans' with 'method' on 'map' from reference.front(), comparing each scan's estimate
// with reference[i] ('reference' has one pose per scan, not empty).
std::vector<TrackedScan> TrackScans(const localization::LocalizerMap& map,
                                    localization::LocalizationMethod method,
                                    const std::vector<StampedScan>& scans,
                                    const std::vector<Pose2>& reference,
                                    const TrackOptions& options);

TrackSummary SummarizeTrack(const std::vector<TrackedScan>& track);

}  // namespace semchain::eval
