#include "apps/track_report.h"

#include <cstdio>
#include <sstream>

namespace semchain::app {
namespace {

std::string Fixed(const nlohmann::json& value, int digits) {
  if (value.is_null()) return "n/a";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", digits, value.get<double>());
  return buffer;
}

nlohmann::json Spread(std::vector<double> values) {
  return {{"median", eval::Percentile(values, 50.0)},
          {"p95", eval::Percentile(values, 95.0)},
          {"max", eval::Percentile(values, 100.0)}};
}

}  // namespace

nlohmann::json SummaryJson(const eval::TrackSummary& s, const TrackTarget& target) {
  const bool within = s.estimated == s.scans && s.median_m <= target.median_m &&
                      s.median_deg <= target.median_deg && s.max_m <= target.max_m &&
                      s.max_deg <= target.max_deg;
  return {{"scans", s.scans},
          {"estimated", s.estimated},
          {"updates", s.updates},
          {"scan_matched", s.scan_matched},
          {"median_m", s.median_m},
          {"p95_m", s.p95_m},
          {"max_m", s.max_m},
          {"median_deg", s.median_deg},
          {"p95_deg", s.p95_deg},
          {"max_deg", s.max_deg},
          {"cpu_ms_per_update", s.cpu_ms_per_update},
          {"cpu_ms_per_scan", s.cpu_ms_per_scan},
          {"within_target", within}};
}

nlohmann::json OverTargetJson(const std::vector<eval::TrackedScan>& track,
                              const std::vector<eval::ReferenceCheck>& checks,
                              const TrackTarget& target) {
  int over = 0, fits_better = 0, not_matched = 0;
  for (std::size_t i = 0; i < track.size(); ++i) {
    const eval::TrackedScan& s = track[i];
    if (!s.estimated || (s.error_m <= target.max_m && s.error_deg <= target.max_deg)) continue;
    ++over;
    if (!s.scan_matched) {
      ++not_matched;
    } else if (checks[i].points > 0 && s.score > checks[i].score) {
      ++fits_better;
    }
  }
  return {{"scans", over},
          {"estimate_fits_map_better", fits_better},
          {"not_matched", not_matched},
          {"other", over - fits_better - not_matched}};
}

nlohmann::json ReferenceJson(const std::vector<eval::ReferenceCheck>& checks) {
  std::vector<double> motion_m, motion_deg, fit_m, fit_deg, score;
  for (const eval::ReferenceCheck& c : checks) {
    motion_m.push_back(c.motion_m);
    motion_deg.push_back(c.motion_deg);
    if (c.points == 0) continue;
    fit_m.push_back(c.fit_m);
    fit_deg.push_back(c.fit_deg);
    score.push_back(c.score);
  }
  return {{"motion_m", Spread(motion_m)}, {"motion_deg", Spread(motion_deg)},
          {"fit_m", Spread(fit_m)},       {"fit_deg", Spread(fit_deg)},
          {"score", Spread(score)},       {"scans_without_returns", checks.size() - fit_m.size()}};
}

std::string TrackMarkdown(const nlohmann::json& results) {
  std::ostringstream md;
  const nlohmann::json& target = results["target"];
  const nlohmann::json& amcl = results["amcl"];
  md << "# semchain bench track\n\n"
     << "source: `" << results["source"].get<std::string>() << "`, " << results["scans"]
     << " scans; map and reference trajectory: " << results["map"]["from"].get<std::string>()
     << "; every scan tracked from the reference's first pose. AMCL: " << amcl["max_particles"]
     << " particles, " << amcl["max_beams"] << " beams ("
     << amcl["beam_selection"].get<std::string>() << "), updates every "
     << Fixed(amcl["update_min_d"], 3) << " m / " << Fixed(amcl["update_min_a"], 3)
     << " rad; scan tracking " << (results["scan_tracking"].get<bool>() ? "on" : "off")
     << ". Target: median ≤ " << Fixed(target["median_m"], 2) << " m and "
     << Fixed(target["median_deg"], 1) << "°, max ≤ " << Fixed(target["max_m"], 2) << " m and "
     << Fixed(target["max_deg"], 1) << "°.\n\n"
     << "| method | median (m) | p95 (m) | max (m) | median (°) | p95 (°) | max (°) | updates "
        "| scans matched | CPU per update (ms) | CPU per scan (ms) | within target "
        "| over max: fits the map better / not matched / other |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [method, m] : results["methods"].items()) {
    md << "| " << method << " | " << Fixed(m["median_m"], 3) << " | " << Fixed(m["p95_m"], 3)
       << " | " << Fixed(m["max_m"], 3) << " | " << Fixed(m["median_deg"], 2) << " | "
       << Fixed(m["p95_deg"], 2) << " | " << Fixed(m["max_deg"], 2) << " | " << m["updates"]
       << " | " << m["scan_matched"] << " | " << Fixed(m["cpu_ms_per_update"], 2) << " | "
       << Fixed(m["cpu_ms_per_scan"], 2) << " | " << (m["within_target"].get<bool>() ? "yes" : "no")
       << " | ";
    const nlohmann::json& o = m["over_target"];
    md << o["scans"] << ": " << o["estimate_fits_map_better"] << " / " << o["not_matched"] << " / "
       << o["other"] << " |\n";
  }
  const nlohmann::json& r = results["reference"];
  md << "\nA scan over the target's max whose estimate fits the map better than the reference pose "
        "(the scan matcher's score) marks a place where the map, drawn from every visit, "
        "disagrees with its own trajectory: there the map is at fault, not the tracker.\n";
  md << "\nThe reference trajectory itself (median / p95 / max over the scans):\n\n"
     << "| measure | median | p95 | max |\n|---|---|---|---|\n";
  const auto row = [&](const char* name, const char* key, int digits) {
    md << "| " << name << " | " << Fixed(r[key]["median"], digits) << " | "
       << Fixed(r[key]["p95"], digits) << " | " << Fixed(r[key]["max"], digits) << " |\n";
  };
  row("motion against odometry, per scan (m)", "motion_m", 3);
  row("motion against odometry, per scan (°)", "motion_deg", 2);
  row("pose against the scan's best fit in the map (m)", "fit_m", 3);
  row("pose against the scan's best fit in the map (°)", "fit_deg", 2);
  row("scan matcher score of the pose (0-1)", "score", 2);
  return md.str();
}

std::string TraceCsv(const std::vector<double>& stamps, const std::vector<Pose2>& reference,
                     const std::vector<eval::ReferenceCheck>& checks,
                     const std::vector<MethodTrack>& tracks) {
  std::ostringstream csv;
  csv.precision(10);
  csv << "scan,stamp,ref_x,ref_y,ref_theta,ref_motion_m,ref_motion_deg,ref_fit_m,ref_fit_deg,"
         "ref_score,ref_points";
  for (const MethodTrack& t : tracks) {
    const std::string& m = t.method;
    csv << "," << m << "_x," << m << "_y," << m << "_theta," << m << "_error_m," << m
        << "_error_deg," << m << "_score," << m << "_matched," << m << "_updates," << m
        << "_cpu_ms";
  }
  csv << "\n";
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    const eval::ReferenceCheck& c = checks[i];
    csv << i << "," << stamps[i] << "," << reference[i].x << "," << reference[i].y << ","
        << reference[i].theta << "," << c.motion_m << "," << c.motion_deg << "," << c.fit_m << ","
        << c.fit_deg << "," << c.score << "," << c.points;
    for (const MethodTrack& t : tracks) {
      const eval::TrackedScan& s = t.scans[i];
      if (s.estimated) {
        csv << "," << s.estimate.x << "," << s.estimate.y << "," << s.estimate.theta << ","
            << s.error_m << "," << s.error_deg << "," << s.score;
      } else {
        csv << ",,,,,,";
      }
      csv << "," << (s.scan_matched ? 1 : 0) << "," << s.updates << "," << s.cpu_ms;
    }
    csv << "\n";
  }
  return csv.str();
}

}  // namespace semchain::app
