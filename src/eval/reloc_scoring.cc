#include "eval/reloc_scoring.h"

#include <cmath>

#include "core/angles.h"

namespace semchain::eval {

namespace {

// The first pre-localization's error against the truth at its scan (and, with 'map_frame', in
// the map's frame), when there was one.
void ScorePreLocalization(const localization::RelocTrace& trace,
                          const std::vector<StampedPose>& truth, const MapFrame* map_frame,
                          RelocTrialOutcome* outcome) {
  if (!trace.prelocalization || trace.prelocalization_scan < 0) return;
  outcome->prelocalized = true;
  const Pose2& t = truth[static_cast<std::size_t>(trace.prelocalization_scan)].pose;
  outcome->prelocalization_error =
      (trace.prelocalization->translation() - t.translation()).cwiseAbs();
  outcome->prelocalization_error_rad =
      std::abs(NormalizeAngle(trace.prelocalization->theta - t.theta));
  if (map_frame != nullptr) {
    outcome->prelocalization_error_map =
        (trace.prelocalization->translation() - map_frame->FromWorld(t).translation()).cwiseAbs();
  }
}

}  // namespace

RelocTrialOutcome ScoreRelocTrace(const localization::RelocTrace& trace,
                                  const std::vector<StampedPose>& truth,
                                  const RelocBenchmarkOptions& options, const MapFrame* map_frame) {
  RelocTrialOutcome outcome;
  const std::size_t n = trace.estimates.size();
  const auto within = [&](std::size_t i) {
    if (!trace.estimates[i]) return false;
    const Pose2& e = *trace.estimates[i];
    const Pose2& t = truth[i].pose;
    return (e.translation() - t.translation()).norm() <= options.success_distance &&
           std::abs(NormalizeAngle(e.theta - t.theta)) <= options.success_heading;
  };
  // The first scan from which the estimate stays within the tolerance to the end.
  std::size_t first = n;
  for (std::size_t i = n; i-- > 0;) {
    if (!within(i)) break;
    first = i;
  }
  ScorePreLocalization(trace, truth, map_frame, &outcome);
  if (n > 0 && trace.estimates.back()) {
    outcome.localized = true;
    const Pose2& e = *trace.estimates.back();
    const Pose2& t = truth.back().pose;
    outcome.final_error_m = (e.translation() - t.translation()).norm();
    outcome.final_error_rad = std::abs(NormalizeAngle(e.theta - t.theta));
  }
  // A failed trial is charged what the method spent over the whole time it had: the trial up
  // to the time limit.
  const auto charge_until = [&](std::size_t last) {
    outcome.time = truth[last].timestamp - truth.front().timestamp;
    outcome.cpu = trace.cpu_seconds[last];
    outcome.search_cpu = trace.search_cpu_seconds[last];
  };
  const auto charge_failure = [&] {
    if (n == 0) return;
    std::size_t last = 0;
    while (last + 1 < n &&
           truth[last + 1].timestamp - truth.front().timestamp <= options.time_limit) {
      ++last;
    }
    charge_until(last);
  };
  if (first == n || truth[first].timestamp - truth.front().timestamp > options.time_limit) {
    charge_failure();
    return outcome;
  }
  charge_until(first);
  outcome.success = true;
  outcome.iterations = trace.iterations[first];
  const Pose2& e = *trace.estimates.back();
  const Pose2& t = truth.back().pose;
  outcome.error_m = (e.translation() - t.translation()).norm();
  outcome.error_rad = std::abs(NormalizeAngle(e.theta - t.theta));
  return outcome;
}

void AccumulateRelocOutcome(const RelocTrialOutcome& outcome, RelocMethodStats* stats) {
  ++stats->trials;
  if (outcome.prelocalized) {
    ++stats->prelocalized;
    stats->prelocalization_error_x_m += outcome.prelocalization_error.x();
    stats->prelocalization_error_y_m += outcome.prelocalization_error.y();
    stats->prelocalization_error_deg += outcome.prelocalization_error_rad * 180.0 / M_PI;
    stats->prelocalization_error_map_x_m += outcome.prelocalization_error_map.x();
    stats->prelocalization_error_map_y_m += outcome.prelocalization_error_map.y();
  }
  stats->mean_time_all_s += outcome.time;
  stats->mean_cpu_all_ms += 1000.0 * outcome.cpu;
  stats->mean_search_cpu_all_ms += 1000.0 * outcome.search_cpu;
  if (!outcome.success) return;
  ++stats->successes;
  stats->mean_time_s += outcome.time;
  stats->mean_cpu_ms += 1000.0 * outcome.cpu;
  stats->mean_search_cpu_ms += 1000.0 * outcome.search_cpu;
  stats->mean_iterations += outcome.iterations;
  stats->mean_error_m += outcome.error_m;
  stats->mean_error_deg += outcome.error_rad * 180.0 / M_PI;
}

void FinishRelocStats(RelocMethodStats* stats) {
  stats->success_rate = stats->trials > 0 ? double(stats->successes) / stats->trials : 0.0;
  if (stats->trials > 0) {
    stats->mean_time_all_s /= stats->trials;
    stats->mean_cpu_all_ms /= stats->trials;
    stats->mean_search_cpu_all_ms /= stats->trials;
  }
  if (stats->successes > 0) {
    const double n = stats->successes;
    stats->mean_time_s /= n;
    stats->mean_cpu_ms /= n;
    stats->mean_search_cpu_ms /= n;
    stats->mean_iterations /= n;
    stats->mean_error_m /= n;
    stats->mean_error_deg /= n;
  }
  if (stats->prelocalized > 0) {
    stats->prelocalization_error_x_m /= stats->prelocalized;
    stats->prelocalization_error_y_m /= stats->prelocalized;
    stats->prelocalization_error_deg /= stats->prelocalized;
    stats->prelocalization_error_map_x_m /= stats->prelocalized;
    stats->prelocalization_error_map_y_m /= stats->prelocalized;
  }
}

RelocTrialRecord RelocTrialRecordOf(int trial, const Pose2& start,
                                    const localization::RelocTrace& trace,
                                    const RelocTrialOutcome& outcome) {
  RelocTrialRecord record;
  record.trial = trial;
  record.start[0] = start.x;
  record.start[1] = start.y;
  record.start[2] = start.theta;
  record.success = outcome.success;
  record.time_s = outcome.time;
  record.cpu_ms = 1000.0 * outcome.cpu;
  record.search_cpu_ms = 1000.0 * outcome.search_cpu;
  if (!trace.search_cpu_seconds.empty()) {
    record.search_cpu_trial_ms = 1000.0 * trace.search_cpu_seconds.back();
  }
  record.localized = outcome.localized;
  record.error_m = outcome.final_error_m;
  record.error_deg = outcome.final_error_rad * 180.0 / M_PI;
  record.prelocalizations = trace.prelocalizations;
  record.single_object_prelocalizations = trace.single_object_prelocalizations;
  record.undecided_prelocalizations = trace.undecided_prelocalizations;
  record.lock_corrections = trace.lock_corrections;
  record.lock_rechecks = trace.lock_rechecks;
  if (outcome.prelocalized) {
    record.prelocalization_error =
        Eigen::Vector3d(outcome.prelocalization_error.x(), outcome.prelocalization_error.y(),
                        outcome.prelocalization_error_rad * 180.0 / M_PI);
    record.prelocalization_error_map = outcome.prelocalization_error_map;
  }
  return record;
}

}  // namespace semchain::eval
