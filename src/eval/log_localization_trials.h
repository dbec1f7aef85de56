#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "localization/amcl_options.h"
#include "localization/scan_match_relocalizer.h"
#include "mapping/map_io.h"
#include "mapping/odometry_perturbation.h"
#include "sensors/laser_scan.h"

// Global localization (kidnapped robot) on a real log with corrected poses
// (`semchain bench localize`): the map is built from the corrected poses (not by SLAM); each
// trial starts at a random scan with the pose unknown and runs a method over the following
// scans. Two protocols (LogTrialOptions, Nav2Protocol):
// - semchain: the log's odometry as it is; a trial succeeds when the estimate comes within
//   success_distance / success_angle of the corrected pose and stays there until the trial
//   ends; its time is the log time from the start scan to the first update of that final streak.
// - nav2 (the peer's set-up, DESIGN.md §6): odometry = corrected poses + seeded noise; a trial
//   succeeds when the estimate is within the tolerances for success_updates consecutive
//   updates, and ends there; its time is the log time to the update that completes the streak.
namespace semchain::eval {

struct LogTrialOptions {
  int trials = 20;
  std::uint64_t seed = 1;
  // Seeds the filters' random streams instead of 'seed', which keeps the trial starts and the
  // odometry noise: the spread of a result over filter streams on the same trials.
  std::optional<std::uint64_t> filter_seed;
  std::string method = "amcl";  // amcl | scanmatch-global
  // A trial covers this much log time after its start scan (start scans are drawn among those
  // with that much log left). Logs whose timestamps do not increase use window_scans instead.
  double window_seconds = 120.0;
  int window_scans = 300;
  double success_distance_meters = 0.25;
  double success_angle_radians = 0.17453292519943295;  // 10°
  // The map: cells of this size, returns up to this range (far returns smear walls).
  double map_resolution = 0.05;
  double map_max_range_meters = 30.0;
  localization::AmclOptions amcl;
  localization::ScanMatchRelocalizerOptions relocalizer;
  // scanmatch-global: attempts on scans spaced like AMCL updates (update_min_d / update_min_a)
  // until one reaches the minimum score.
  int max_relocalization_attempts = 10;
  // 0: success = within the tolerances from some update to the trial's end (semchain). n > 0:
  // within them for n consecutive updates, the trial ending there (nav2 protocol).
  int success_updates = 0;
  // Odometry = the corrected poses' increments with this seeded noise (nav2 protocol); the
  // caller perturbs the log (mapping::PerturbOdometry) and passes the corrected poses as truth.
  bool perturb_odometry = false;
  mapping::OdometryPerturbationOptions odometry_noise;

  bool Validate(std::string* error) const;
};

// The peer's protocol (DESIGN.md §6), on top of 'base' (trials, seed, method kept): nav2 AMCL
// defaults with 20000 / 500 particles, KLD ε 0.05 / δ 0.99 (pf_z 0.99), likelihood field z_hit
// 0.5 / z_rand 0.5 / σ_hit 0.2, 60 beams, alphas 0.2, updates at 0.25 m / 0.2 rad; odometry =
// corrected poses + seeded Gaussian noise per scan increment (σ_xy = 0.05 m/m + 0.01 m/rad,
// σ_θ = 0.02 rad/m + 0.05 rad/rad, no systematic error, seed = the bench seed); success = the
// best cluster within 0.25 m and 10° for 5 consecutive updates; 60 s of log per trial.
LogTrialOptions Nav2Protocol(LogTrialOptions base);

struct LogTrial {
  int trial = 0;
  int start_scan = 0;
  bool success = false;
  std::optional<double> time_s;  // log seconds to converge (successes with usable timestamps)
  // nav2 rule: log seconds to the first update of the streak that made it a success (time_s is
  // to the update completing it).
  std::optional<double> streak_start_time_s;
  int scans_to_converge = 0;  // scans from the start scan to convergence (successes)
  double distance_m = 0.0;    // odometry distance driven until convergence (successes)
  int iterations = 0;         // filter updates / match attempts until convergence or the end
  int updates = 0;            // filter updates / match attempts run in the whole trial
  double cpu_ms = 0.0;        // CPU time of the whole trial
  double error_m = 0.0;       // final estimate's error
  double error_deg = 0.0;
  bool estimated = false;  // the method produced an estimate at all
  // Weaker criteria, for reading the strict one: the estimate came within the tolerances at
  // least once (and when, in log seconds), and it is within them at the trial's end.
  bool reached = false;
  std::optional<double> reach_time_s;
  bool final_within = false;
};

struct LogTrialSummary {
  int trials = 0;
  int successes = 0;
  double success_rate = 0.0;
  std::optional<double> mean_time_s;    // successes only
  std::optional<double> median_time_s;  // successes only
  // nav2 rule: the same to the first update of the successful streak (successes only).
  std::optional<double> mean_streak_start_time_s;
  std::optional<double> median_streak_start_time_s;
  double mean_scans = 0.0;         // successes only
  double mean_distance_m = 0.0;    // successes only
  double mean_iterations = 0.0;    // successes only
  double mean_cpu_ms = 0.0;        // all trials
  double cpu_ms_per_update = 0.0;  // all trials: CPU over filter updates / match attempts
  double mean_error_m = 0.0;       // successes only
  double mean_error_deg = 0.0;
  int reached = 0;                          // trials whose estimate was ever within tolerance
  std::optional<double> mean_reach_time_s;  // ... and how soon (those trials)
  int final_within = 0;                     // trials within tolerance at their end
};

// Occupancy map from the scans at their logged poses (StampedScan::odometry, the corrected
// robot pose in a corrected log), thresholded as map_saver does.
mapping::MapImage MapFromCorrectedPoses(const std::vector<StampedScan>& scans, double resolution,
                                        double max_range_meters);

// True when the scan timestamps never decrease and span a plausible time (MIT Killian's corrected
// log has timestamps that wrap to 4.29e9).
bool TimestampsUsable(const std::vector<StampedScan>& scans);

// Runs the trials on 'scans' against 'map'. The truth is 'truth' (the robot's corrected pose
// for every scan, when the scans carry perturbed odometry) or, when it is empty, the scans'
// own odometry (a corrected log). 'progress' (may be empty) is called with the number of
// trials done.
std::vector<LogTrial> RunLogTrials(const std::vector<StampedScan>& scans,
                                   const mapping::MapImage& map, const LogTrialOptions& options,
                                   const std::function<void(int)>& progress = {},
                                   const std::vector<Pose2>& truth = {});

LogTrialSummary Summarize(const std::vector<LogTrial>& trials);

}  // namespace semchain::eval
