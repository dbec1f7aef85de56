#pragma once

#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "mapping/hill_climbing_matcher.h"
#include "mapping/likelihood_field.h"
#include "mapping/motion_model.h"
#include "mapping/occupancy_grid.h"
#include "mapping/prepared_scan.h"
#include "mapping/surface_refinement.h"
#include "sensors/laser_scan.h"

// Scan-matched odometry (beyond the papers): every scan is matched against a small local map
// built from the scans just before it, starting from the wheel odometry's prediction, and the
// matched poses replace the wheel odometry that the RBPF sees. Wheel odometry on real robots
// drifts by degrees within a metre (mit-csail), so the RBPF's scan matcher would otherwise
// start far from the right pose whenever it processes a scan; locally the laser is much better.
// The local maps are submaps (Cartographer's idea): two overlap, each receives
// 'scans_per_submap' scans, and scans are matched against the older, fuller one.
namespace semchain::mapping {

struct LaserOdometryOptions {
  bool enabled = true;  // false: the RBPF uses the wheel odometry as logged (GMapping)
  int scans_per_submap = 80;
  // A match with fewer endpoints on obstacles (or than a third of the scan's returns, when that is
  // fewer: RequiredMatches) is rejected: the wheel odometry is used instead.
  int min_matched_points = 60;
  double match_max_range_meters = 30.0;
  int match_beam_step = 3;  // hill climbing uses every n-th return (the refinement all)
  HillClimbingOptions matcher;
  // After hill climbing, a Gauss-Newton refinement with the predicted pose as a prior of these
  // standard deviations: where the scan constrains nothing (along a corridor) the prediction
  // stays. Disable to take the hill climber's pose as it is.
  SurfaceRefinementOptions refinement{true, 8, 0.02, 1e-4, 1.0, true};
  MotionModelOptions prior{0.1, 0.1, 0.1, 0.2, 0.02, 0.02};

  bool Validate(std::string* error) const;
};

// The laser odometry fed one scan at a time (each scan is matched against the scans before it
// only, so the batch and the incremental results are the same).
class LaserOdometry {
 public:
  LaserOdometry(const LaserOdometryOptions& options, const OccupancyGridOptions& grid_options,
                const LikelihoodFieldOptions& field_options);
  LaserOdometry(const LaserOdometry&) = delete;
  LaserOdometry& operator=(const LaserOdometry&) = delete;

  // The scan-matched odometry pose of 'scan' ('prepared' is it prepared), the next in time.
  Pose2 Add(const StampedScan& scan, const PreparedScan& prepared);
  int rejected() const { return rejected_; }

 private:
  struct Submap {
    OccupancyGrid grid;
    int scans = 0;
  };

  LaserOdometryOptions options_;
  OccupancyGridOptions grid_options_;
  LikelihoodFieldOptions field_options_;
  MotionModel prior_model_;
  std::deque<Submap> submaps_;
  std::vector<Pose2> poses_;  // the last two
  Pose2 last_odometry_;
  int rejected_ = 0;
};

// Returns the scan-matched odometry pose of every scan (the first scan keeps its wheel
// odometry pose, so the frame is unchanged). 'rejected' (optional) receives the number of
// scans whose match was rejected.
std::vector<Pose2> ComputeLaserOdometry(const std::vector<StampedScan>& scans,
                                        const std::vector<PreparedScan>& prepared,
                                        const LaserOdometryOptions& options,
                                        const OccupancyGridOptions& grid_options,
                                        const LikelihoodFieldOptions& field_options,
                                        int* rejected = nullptr);

}  // namespace semchain::mapping
