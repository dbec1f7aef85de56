#include "localization/log_localization_trials.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "core/angles.h"
#include "core/check.h"
#include "core/cpu_time.h"
#include "localization/amcl.h"
#include "mapping/prepared_scan.h"
#include "mapping/ray_casting.h"

namespace semchain::localization {
namespace {

struct Error {
  double meters = 0.0;
  double degrees = 0.0;
};

Error ErrorOf(const Pose2& estimate, const Pose2& truth) {
  return {std::hypot(estimate.x - truth.x, estimate.y - truth.y),
          std::abs(RadToDeg(AngleDifference(estimate.theta, truth.theta)))};
}

// The scans of one trial: [start, end].
struct Span {
  int start = 0;
  int end = 0;
};

class TrialRunner {
 public:
  TrialRunner(const std::vector<StampedScan>& scans, const LogTrialOptions& options)
      : scans_(scans), options_(options), timed_(TimestampsUsable(scans)) {}

  bool Ok(const Error& e) const {
    return e.meters <= options_.success_distance_meters &&
           e.degrees <= RadToDeg(options_.success_angle_radians);
  }
  // The trial's start scans, drawn once so that every method sees the same trials.
  std::vector<Span> Spans() const {
    const int n = static_cast<int>(scans_.size());
    int last_start = n - 1;
    if (timed_) {
      const double end_time = scans_.back().scan.timestamp - options_.window_seconds;
      while (last_start > 0 && scans_[last_start].scan.timestamp > end_time) --last_start;
    } else {
      last_start = std::max(0, n - 1 - options_.window_scans);
    }
    Rng rng = MakeRng(options_.seed, 0);
    std::uniform_int_distribution<int> pick(0, last_start);
    std::vector<Span> spans;
    for (int t = 0; t < options_.trials; ++t) {
      Span span{pick(rng), 0};
      span.end = span.start;
      while (span.end + 1 < n && InWindow(span.start, span.end + 1)) ++span.end;
      spans.push_back(span);
    }
    return spans;
  }
  // Fills the convergence fields of 'trial' from the per-update errors.
  void Converge(const std::vector<std::pair<int, Error>>& history, int start,
                LogTrial* trial) const {
    trial->estimated = !history.empty();
    if (history.empty()) return;
    trial->error_m = history.back().second.meters;
    trial->error_deg = history.back().second.degrees;
    trial->iterations = static_cast<int>(history.size());
    for (const auto& [scan, error] : history) {
      if (!Ok(error)) continue;
      trial->reached = true;
      if (timed_) trial->reach_time_s = scans_[scan].scan.timestamp - scans_[start].scan.timestamp;
      break;
    }
    trial->final_within = Ok(history.back().second);
    if (!trial->final_within) return;
    std::size_t first = history.size() - 1;
    while (first > 0 && Ok(history[first - 1].second)) --first;
    const int scan = history[first].first;
    trial->success = true;
    trial->iterations = static_cast<int>(first) + 1;
    trial->scans_to_converge = scan - start;
    if (timed_) trial->time_s = scans_[scan].scan.timestamp - scans_[start].scan.timestamp;
    for (int i = start; i < scan; ++i) {
      trial->distance_m +=
          (scans_[i + 1].odometry.translation() - scans_[i].odometry.translation()).norm();
    }
  }

 private:
  bool InWindow(int start, int i) const {
    if (!timed_) return i - start <= options_.window_scans;
    return scans_[i].scan.timestamp - scans_[start].scan.timestamp <= options_.window_seconds;
  }

  const std::vector<StampedScan>& scans_;
  const LogTrialOptions& options_;
  bool timed_;
};

LogTrial RunAmclTrial(const std::vector<StampedScan>& scans, const LocalizationMap& map,
                      const TrialRunner& runner, const LogTrialOptions& options, int t,
                      const Span& span) {
  LogTrial trial;
  trial.trial = t;
  trial.start_scan = span.start;
  const double cpu_start = ProcessCpuSeconds();
  Amcl amcl(map, options.amcl, MakeRng(options.seed, 1 + static_cast<std::uint64_t>(t)));
  amcl.InitializeGlobal();
  std::vector<std::pair<int, Error>> history;
  for (int i = span.start; i <= span.end; ++i) {
    const StampedScan& s = scans[static_cast<std::size_t>(i)];
    if (amcl.ProcessScan(s.scan, s.odometry, s.LaserOffset())) {
      history.emplace_back(i, ErrorOf(amcl.Estimate().pose, s.odometry));
    }
  }
  trial.cpu_ms = 1000.0 * (ProcessCpuSeconds() - cpu_start);
  runner.Converge(history, span.start, &trial);
  return trial;
}

LogTrial RunScanMatchTrial(const std::vector<StampedScan>& scans,
                           const ScanMatchRelocalizer& relocalizer, const TrialRunner& runner,
                           const LogTrialOptions& options, int t, const Span& span) {
  LogTrial trial;
  trial.trial = t;
  trial.start_scan = span.start;
  std::vector<std::pair<int, Error>> history;
  std::optional<Pose2> last;
  int attempts = 0;
  double cpu = 0.0;
  for (int i = span.start; i <= span.end && attempts < options.max_relocalization_attempts; ++i) {
    const StampedScan& s = scans[static_cast<std::size_t>(i)];
    if (last && std::abs(s.odometry.x - last->x) <= options.amcl.update_min_d &&
        std::abs(s.odometry.y - last->y) <= options.amcl.update_min_d &&
        std::abs(AngleDifference(s.odometry.theta, last->theta)) <= options.amcl.update_min_a) {
      continue;
    }
    last = s.odometry;
    ++attempts;
    const RelocalizationResult result = relocalizer.RelocalizeGlobal(s.scan, s.LaserOffset());
    cpu += result.cpu_seconds;
    if (!result.success) continue;
    history.emplace_back(i, ErrorOf(result.pose, s.odometry));
    break;  // one accepted match ends the trial (a relocalizer, not a tracker)
  }
  trial.cpu_ms = 1000.0 * cpu;
  runner.Converge(history, span.start, &trial);
  if (!trial.estimated) trial.iterations = attempts;
  return trial;
}

}  // namespace

bool LogTrialOptions::Validate(std::string* error) const {
  if (trials < 1) {
    *error = "trials must be >= 1";
    return false;
  }
  if (method != "amcl" && method != "scanmatch-global") {
    *error = "method must be amcl or scanmatch-global, not '" + method + "'";
    return false;
  }
  if (!(window_seconds > 0.0) || window_scans < 1) {
    *error = "the trial window must be positive";
    return false;
  }
  if (!(success_distance_meters > 0.0 && success_angle_radians > 0.0)) {
    *error = "success tolerances must be positive";
    return false;
  }
  if (!(map_resolution > 0.0 && map_max_range_meters > 0.0)) {
    *error = "map_resolution and map_max_range_meters must be positive";
    return false;
  }
  if (max_relocalization_attempts < 1) {
    *error = "max_relocalization_attempts must be >= 1";
    return false;
  }
  return amcl.Validate(error) && relocalizer.Validate(error);
}

mapping::MapImage MapFromCorrectedPoses(const std::vector<StampedScan>& scans, double resolution,
                                        double max_range_meters) {
  mapping::OccupancyGridOptions grid_options;
  grid_options.resolution_meters = resolution;
  mapping::OccupancyGrid grid(grid_options);
  mapping::ScanPreparationOptions preparation;
  preparation.max_range_meters = max_range_meters;
  mapping::ScanInserter inserter;
  for (const StampedScan& s : scans) {
    inserter.Insert(mapping::PrepareScan(s.scan, s.LaserOffset(), preparation), s.odometry, &grid);
  }
  return mapping::GridToMapImage(grid);
}

bool TimestampsUsable(const std::vector<StampedScan>& scans) {
  if (scans.size() < 2) return false;
  for (std::size_t i = 1; i < scans.size(); ++i) {
    const double dt = scans[i].scan.timestamp - scans[i - 1].scan.timestamp;
    if (!(dt >= 0.0) || dt > 3600.0) return false;
  }
  return scans.back().scan.timestamp > scans.front().scan.timestamp;
}

std::vector<LogTrial> RunLogTrials(const std::vector<StampedScan>& scans,
                                   const mapping::MapImage& map, const LogTrialOptions& options,
                                   const std::function<void(int)>& progress) {
  std::string error;
  SEMCHAIN_CHECK(options.Validate(&error));
  SEMCHAIN_CHECK(!scans.empty());
  const TrialRunner runner(scans, options);
  const std::vector<Span> spans = runner.Spans();
  std::vector<LogTrial> trials;
  if (options.method == "amcl") {
    const LocalizationMap localization_map(map, options.amcl.laser_likelihood_max_dist);
    for (int t = 0; t < options.trials; ++t) {
      trials.push_back(RunAmclTrial(scans, localization_map, runner, options, t, spans[t]));
      if (progress) progress(t + 1);
    }
  } else {
    const ScanMatchRelocalizer relocalizer(map, options.relocalizer);
    for (int t = 0; t < options.trials; ++t) {
      trials.push_back(RunScanMatchTrial(scans, relocalizer, runner, options, t, spans[t]));
      if (progress) progress(t + 1);
    }
  }
  return trials;
}

LogTrialSummary Summarize(const std::vector<LogTrial>& trials) {
  LogTrialSummary summary;
  summary.trials = static_cast<int>(trials.size());
  double time_sum = 0.0, reach_sum = 0.0;
  int timed = 0, reach_timed = 0;
  for (const LogTrial& t : trials) {
    summary.mean_cpu_ms += t.cpu_ms;
    summary.reached += t.reached ? 1 : 0;
    summary.final_within += t.final_within ? 1 : 0;
    if (t.reach_time_s) {
      reach_sum += *t.reach_time_s;
      ++reach_timed;
    }
    if (!t.success) continue;
    ++summary.successes;
    summary.mean_scans += t.scans_to_converge;
    summary.mean_distance_m += t.distance_m;
    summary.mean_iterations += t.iterations;
    summary.mean_error_m += t.error_m;
    summary.mean_error_deg += t.error_deg;
    if (t.time_s) {
      time_sum += *t.time_s;
      ++timed;
    }
  }
  if (summary.trials > 0) {
    summary.mean_cpu_ms /= summary.trials;
    summary.success_rate = static_cast<double>(summary.successes) / summary.trials;
  }
  if (summary.successes > 0) {
    const double s = summary.successes;
    summary.mean_scans /= s;
    summary.mean_distance_m /= s;
    summary.mean_iterations /= s;
    summary.mean_error_m /= s;
    summary.mean_error_deg /= s;
  }
  if (timed > 0) summary.mean_time_s = time_sum / timed;
  if (reach_timed > 0) summary.mean_reach_time_s = reach_sum / reach_timed;
  return summary;
}

}  // namespace semchain::localization
