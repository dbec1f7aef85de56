#include "eval/reloc_results.h"

#include <cstdio>
#include <nlohmann/json.hpp>

#include "localization/localizer.h"

namespace semchain::eval {

namespace {

nlohmann::json MethodStatsJson(const RelocMethodStats& s) {
  return {{"trials", s.trials},
          {"successes", s.successes},
          {"success_rate", s.success_rate},
          {"mean_time_s", s.mean_time_s},
          {"mean_cpu_ms", s.mean_cpu_ms},
          {"mean_search_cpu_ms", s.mean_search_cpu_ms},
          {"mean_time_all_s", s.mean_time_all_s},
          {"mean_cpu_all_ms", s.mean_cpu_all_ms},
          {"mean_search_cpu_all_ms", s.mean_search_cpu_all_ms},
          {"mean_iterations", s.mean_iterations},
          {"mean_error_m", s.mean_error_m},
          {"mean_error_deg", s.mean_error_deg},
          {"prelocalized", s.prelocalized},
          {"prelocalization_error_x_m", s.prelocalization_error_x_m},
          {"prelocalization_error_y_m", s.prelocalization_error_y_m},
          {"prelocalization_error_deg", s.prelocalization_error_deg},
          {"prelocalization_error_map_x_m", s.prelocalization_error_map_x_m},
          {"prelocalization_error_map_y_m", s.prelocalization_error_map_y_m}};
}

nlohmann::json TrialRecordJson(const RelocTrialRecord& r) {
  nlohmann::json prelocalization_error = nullptr;
  if (r.prelocalization_error) {
    prelocalization_error = {r.prelocalization_error->x(), r.prelocalization_error->y(),
                             r.prelocalization_error->z()};
  }
  nlohmann::json prelocalization_error_map = nullptr;
  if (r.prelocalization_error_map) {
    prelocalization_error_map = {r.prelocalization_error_map->x(),
                                 r.prelocalization_error_map->y()};
  }
  return {{"trial", r.trial},
          {"start", {r.start[0], r.start[1], r.start[2]}},
          {"success", r.success},
          {"time_s", r.time_s},
          {"cpu_ms", r.cpu_ms},
          {"search_cpu_ms", r.search_cpu_ms},
          {"search_cpu_trial_ms", r.search_cpu_trial_ms},
          {"localized", r.localized},
          {"error_m", r.error_m},
          {"error_deg", r.error_deg},
          {"prelocalizations", r.prelocalizations},
          {"single_object_prelocalizations", r.single_object_prelocalizations},
          {"undecided_prelocalizations", r.undecided_prelocalizations},
          {"lock_corrections", r.lock_corrections},
          {"lock_rechecks", r.lock_rechecks},
          {"prelocalization_error", prelocalization_error},
          {"prelocalization_error_map", prelocalization_error_map}};
}

}  // namespace

std::string RelocResultsJson(const RelocBenchmarkResult& result) {
  nlohmann::json methods = nlohmann::json::object();
  for (const auto& [name, s] : result.methods) methods[name] = MethodStatsJson(s);
  nlohmann::json runs = nlohmann::json::object();
  for (const auto& [name, records] : result.runs) {
    nlohmann::json list = nlohmann::json::array();
    for (const RelocTrialRecord& r : records) list.push_back(TrialRecordJson(r));
    runs[name] = list;
  }
  const nlohmann::json root = {{"world", result.world},
                               {"live_world", result.live_world},
                               {"detections", result.detections_source},
                               {"trials", result.trials},
                               {"seed", result.seed},
                               {"map_objects", result.map_objects},
                               {"map_ate_m", result.map_ate_m},
                               {"trial_protocol",
                                {{"turns", result.trial_turns},
                                 {"forward_m", result.trial_forward},
                                 {"face_open", result.trial_face_open},
                                 {"turns_after", result.trial_turns_after}}},
                               {"methods", methods},
                               {"runs", runs}};
  return root.dump(2) + "\n";
}

std::string RelocResultsMarkdown(const RelocBenchmarkResult& result) {
  std::string text = "# bench reloc\n\nworld `" + result.world + "`, live world `" +
                     result.live_world + "`, " + std::to_string(result.trials) + " trials, seed " +
                     std::to_string(result.seed) + "; map from SLAM (ATE " +
                     std::to_string(result.map_ate_m) + " m), " +
                     std::to_string(result.map_objects) +
                     " objects; detections: " + result.detections_source + "\n\n";
  const auto turns = [](double n) { return n == 1.0 ? "turn" : "turns"; };
  char protocol[256];
  std::snprintf(protocol, sizeof(protocol),
                "Trials: %g %s in place, then a drive of at most %g m %s", result.trial_turns,
                turns(result.trial_turns), result.trial_forward,
                result.trial_face_open ? "towards the most open heading" : "straight on");
  text += protocol;
  if (result.trial_turns_after > 0.0) {
    std::snprintf(protocol, sizeof(protocol), ", then %g more %s in place there",
                  result.trial_turns_after, turns(result.trial_turns_after));
    text += protocol;
  }
  text += ".\n\n";
  text +=
      "Time, CPU and search CPU: means over the successful trials (until convergence), then "
      "over all trials (a failed trial charged for its whole time, up to the limit). "
      "Pre-localization error: the first hypothesis a method accepted, against the truth and "
      "against the truth carried into the SLAM map's frame (the map's own error taken out).\n\n"
      "| method | success | mean time (s) | mean CPU (ms) | search CPU (ms) | all trials: "
      "time (s) / CPU (ms) / search CPU (ms) | iterations | error (m) | error (deg) "
      "| pre-localization error x / y (m) | in the map's frame x / y (m) |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [name, s] : result.methods) {
    const bool scan_matcher =
        localization::IsScanMatcherMethod(*localization::ParseLocalizationMethod(name));
    char search_cpu[32] = "–";
    char search_cpu_all[32] = "–";
    if (scan_matcher) {
      std::snprintf(search_cpu, sizeof(search_cpu), "%.2f", s.mean_search_cpu_ms);
      std::snprintf(search_cpu_all, sizeof(search_cpu_all), "%.2f", s.mean_search_cpu_all_ms);
    }
    char prelocalization[64] = "–";
    char prelocalization_map[64] = "–";
    if (s.prelocalized > 0) {
      std::snprintf(prelocalization, sizeof(prelocalization), "%.3f / %.3f",
                    s.prelocalization_error_x_m, s.prelocalization_error_y_m);
      std::snprintf(prelocalization_map, sizeof(prelocalization_map), "%.3f / %.3f",
                    s.prelocalization_error_map_x_m, s.prelocalization_error_map_y_m);
    }
    char line[512];
    std::snprintf(line, sizeof(line),
                  "| %s | %d/%d (%.1f %%) | %.2f | %.1f | %s | %.2f / %.1f / %s | %.1f | %.3f | "
                  "%.2f | %s | %s |\n",
                  name.c_str(), s.successes, s.trials, 100.0 * s.success_rate, s.mean_time_s,
                  s.mean_cpu_ms, search_cpu, s.mean_time_all_s, s.mean_cpu_all_ms, search_cpu_all,
                  s.mean_iterations, s.mean_error_m, s.mean_error_deg, prelocalization,
                  prelocalization_map);
    text += line;
  }
  return text;
}

}  // namespace semchain::eval
