#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eval/reference_check.h"
#include "eval/track_benchmark.h"

// What `semchain bench track` writes: results.json, results.md and trace.csv.
namespace semchain::app {

// The tracking target the summary is checked against (metres, degrees).
struct TrackTarget {
  double median_m = 0.05;
  double median_deg = 1.0;
  double max_m = 0.20;
  double max_deg = 5.0;
};

// One method's tracking run.
struct MethodTrack {
  std::string method;
  std::vector<eval::TrackedScan> scans;
  eval::TrackSummary summary;
};

nlohmann::json SummaryJson(const eval::TrackSummary& s, const TrackTarget& target);
// The scans whose error passes the target's max (metres or degrees), by what the map says of
// them: the estimate fits the map better than the reference pose does (the map, drawn from
// every visit, disagrees with its own trajectory there: the map is at fault, not the tracker),
// scan tracking did not match the scan, or neither (the tracker chose a worse fit).
nlohmann::json OverTargetJson(const std::vector<eval::TrackedScan>& track,
                              const std::vector<eval::ReferenceCheck>& checks,
                              const TrackTarget& target);
// Median, p95 and max of the reference checks (ReferenceCheck's four measures).
nlohmann::json ReferenceJson(const std::vector<eval::ReferenceCheck>& checks);
// results.md from results.json.
std::string TrackMarkdown(const nlohmann::json& results);
// One row per scan: its stamp, the reference pose and its checks, each method's error, updates
// and CPU.
std::string TraceCsv(const std::vector<double>& stamps, const std::vector<Pose2>& reference,
                     const std::vector<eval::ReferenceCheck>& checks,
                     const std::vector<MethodTrack>& tracks);

}  // namespace semchain::app
