#include "eval/log_localization_trials.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "core/angles.h"
#include "core/check.h"
#include "core/cpu_time.h"
#include "eval/statistics.h"
#include "localization/amcl.h"
#include "mapping/prepared_scan.h"
#include "mapping/ray_casting.h"

namespace semchain::eval {
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
  TrialRunner(const std::vector<StampedScan>& scans, const std::vector<Pose2>& truth,
              const LogTrialOptions& options)
      : scans_(scans), truth_(truth), options_(options), timed_(TimestampsUsable(scans)) {
    SEMCHAIN_CHECK(truth_.empty() || truth_.size() == scans_.size());
  }

  // The robot's true pose at scan 'i'.
  const Pose2& Truth(int i) const {
    return truth_.empty() ? scans_[static_cast<std::size_t>(i)].odometry
                          : truth_[static_cast<std::size_t>(i)];
  }
  // The log time from scan 'start' to scan 'i' (empty without usable timestamps).
  std::optional<double> Elapsed(int start, int i) const {
    if (!timed_) return std::nullopt;
    return scans_[i].scan.timestamp - scans_[start].scan.timestamp;
  }

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
  // Fills the convergence fields of 'trial' from the per-update errors. 'streak' 0: success =
  // within tolerance from some update to the end (semchain); n > 0: n consecutive updates
  // within tolerance (nav2), converged at the update completing the first such streak.
  void Converge(const std::vector<std::pair<int, Error>>& history, int start, int streak,
                LogTrial* trial) const {
    trial->estimated = !history.empty();
    trial->updates = static_cast<int>(history.size());
    if (history.empty()) return;
    trial->error_m = history.back().second.meters;
    trial->error_deg = history.back().second.degrees;
    trial->iterations = static_cast<int>(history.size());
    for (const auto& [scan, error] : history) {
      if (!Ok(error)) continue;
      trial->reached = true;
      trial->reach_time_s = Elapsed(start, scan);
      break;
    }
    trial->final_within = Ok(history.back().second);
    const std::optional<std::size_t> converged = ConvergedAt(history, streak);
    if (!converged) return;
    const int scan = history[*converged].first;
    trial->success = true;
    trial->iterations = static_cast<int>(*converged) + 1;
    if (streak > 0) {  // the trial ends at convergence: its error is the one there
      trial->error_m = history[*converged].second.meters;
      trial->error_deg = history[*converged].second.degrees;
      trial->streak_start_time_s = Elapsed(start, history[*converged + 1 - streak].first);
    }
    trial->scans_to_converge = scan - start;
    trial->time_s = Elapsed(start, scan);
    for (int i = start; i < scan; ++i) {
      trial->distance_m +=
          (scans_[i + 1].odometry.translation() - scans_[i].odometry.translation()).norm();
    }
  }
  // The update at which 'history' counts as converged under Converge's rule, if any.
  std::optional<std::size_t> ConvergedAt(const std::vector<std::pair<int, Error>>& history,
                                         int streak) const {
    if (history.empty()) return std::nullopt;
    if (streak > 0) {
      int run = 0;
      for (std::size_t k = 0; k < history.size(); ++k) {
        run = Ok(history[k].second) ? run + 1 : 0;
        if (run >= streak) return k;
      }
      return std::nullopt;
    }
    if (!Ok(history.back().second)) return std::nullopt;
    std::size_t first = history.size() - 1;
    while (first > 0 && Ok(history[first - 1].second)) --first;
    return first;
  }

 private:
  bool InWindow(int start, int i) const {
    if (!timed_) return i - start <= options_.window_scans;
    return scans_[i].scan.timestamp - scans_[start].scan.timestamp <= options_.window_seconds;
  }

  const std::vector<StampedScan>& scans_;
  const std::vector<Pose2>& truth_;
  const LogTrialOptions& options_;
  bool timed_;
};

LogTrial RunAmclTrial(const std::vector<StampedScan>& scans,
                      const localization::LocalizationMap& map, const TrialRunner& runner,
                      const LogTrialOptions& options, int t, const Span& span) {
  LogTrial trial;
  trial.trial = t;
  trial.start_scan = span.start;
  const double cpu_start = ProcessCpuSeconds();
  localization::Amcl amcl(
      map, options.amcl,
      MakeRng(options.filter_seed.value_or(options.seed), 1 + static_cast<std::uint64_t>(t)));
  amcl.InitializeGlobal();
  std::vector<std::pair<int, Error>> history;
  for (int i = span.start; i <= span.end; ++i) {
    const StampedScan& s = scans[static_cast<std::size_t>(i)];
    if (!amcl.ProcessScan(s.scan, s.odometry, s.LaserOffset())) continue;
    history.emplace_back(i, ErrorOf(amcl.Estimate().pose, runner.Truth(i)));
    // nav2 protocol: the trial ends once the streak is complete.
    if (options.success_updates > 0 && runner.ConvergedAt(history, options.success_updates)) break;
  }
  trial.cpu_ms = 1000.0 * (ProcessCpuSeconds() - cpu_start);
  runner.Converge(history, span.start, options.success_updates, &trial);
  return trial;
}

LogTrial RunScanMatchTrial(const std::vector<StampedScan>& scans,
                           const localization::ScanMatchRelocalizer& relocalizer,
                           const TrialRunner& runner, const LogTrialOptions& options, int t,
                           const Span& span) {
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
    const localization::RelocalizationResult result =
        relocalizer.RelocalizeGlobal(s.scan, s.LaserOffset());
    cpu += result.cpu_seconds;
    if (!result.success) continue;
    history.emplace_back(i, ErrorOf(result.pose, runner.Truth(i)));
    break;  // one accepted match ends the trial (a relocalizer, not a tracker)
  }
  trial.cpu_ms = 1000.0 * cpu;
  // Its one estimate decides (under the nav2 protocol too: there is no streak to wait for).
  runner.Converge(history, span.start, options.success_updates > 0 ? 1 : 0, &trial);
  trial.updates = attempts;
  if (!trial.estimated) trial.iterations = attempts;
  return trial;
}

std::optional<double> Mean(const std::vector<double>& values) {
  if (values.empty()) return std::nullopt;
  double sum = 0.0;
  for (const double v : values) sum += v;
  return sum / static_cast<double>(values.size());
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
  if (success_updates < 0) {
    *error = "success_updates must be >= 0";
    return false;
  }
  return amcl.Validate(error) && relocalizer.Validate(error) && odometry_noise.Validate(error);
}

LogTrialOptions Nav2Protocol(LogTrialOptions base) {
  localization::AmclOptions amcl;  // nav2's defaults, then the peer's settings
  amcl.max_particles = 20000;
  amcl.min_particles = 500;
  amcl.pf_err = 0.05;
  amcl.pf_z = 0.99;
  amcl.z_hit = 0.5;
  amcl.sigma_hit = 0.2;
  amcl.max_beams = 60;
  amcl.alpha1 = amcl.alpha2 = amcl.alpha3 = amcl.alpha4 = 0.2;
  amcl.update_min_d = 0.25;
  amcl.update_min_a = 0.2;
  base.amcl = amcl;
  base.window_seconds = 60.0;
  base.success_distance_meters = 0.25;
  base.success_angle_radians = DegToRad(10.0);
  base.success_updates = 5;
  base.perturb_odometry = true;
  mapping::OdometryPerturbationOptions noise;
  noise.seed = base.seed;
  noise.translation_per_meter = 0.05;
  noise.translation_per_radian = 0.01;
  noise.rotation_per_meter = 0.02;
  noise.rotation_per_radian = 0.05;
  noise.distance_scale_error = 0.0;  // noise only: no systematic error
  noise.turn_scale_error = 0.0;
  base.odometry_noise = noise;
  return base;
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
                                   const std::function<void(int)>& progress,
                                   const std::vector<Pose2>& truth) {
  std::string error;
  SEMCHAIN_CHECK(options.Validate(&error));
  SEMCHAIN_CHECK(!scans.empty());
  const TrialRunner runner(scans, truth, options);
  const std::vector<Span> spans = runner.Spans();
  std::vector<LogTrial> trials;
  if (options.method == "amcl") {
    const localization::LocalizationMap localization_map(map,
                                                         options.amcl.laser_likelihood_max_dist);
    for (int t = 0; t < options.trials; ++t) {
      trials.push_back(RunAmclTrial(scans, localization_map, runner, options, t, spans[t]));
      if (progress) progress(t + 1);
    }
  } else {
    const localization::ScanMatchRelocalizer relocalizer(map, options.relocalizer);
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
  double reach_sum = 0.0;
  int reach_timed = 0, updates = 0;
  std::vector<double> times, streak_starts;
  for (const LogTrial& t : trials) {
    if (t.success && t.streak_start_time_s) streak_starts.push_back(*t.streak_start_time_s);
    summary.mean_cpu_ms += t.cpu_ms;
    updates += t.updates;
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
    if (t.time_s) times.push_back(*t.time_s);
  }
  if (updates > 0) summary.cpu_ms_per_update = summary.mean_cpu_ms / updates;
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
  summary.mean_time_s = Mean(times);
  summary.median_time_s = Median(times);
  summary.mean_streak_start_time_s = Mean(streak_starts);
  summary.median_streak_start_time_s = Median(streak_starts);
  if (reach_timed > 0) summary.mean_reach_time_s = reach_sum / reach_timed;
  return summary;
}

}  // namespace semchain::eval
