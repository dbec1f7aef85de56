#include "mapping/laser_odometry.h"

#include <cmath>

#include "core/check.h"
#include "mapping/ray_casting.h"
#include "mapping/required_matches.h"

namespace semchain::mapping {

bool LaserOdometryOptions::Validate(std::string* error) const {
  if (scans_per_submap < 2 || min_matched_points < 0 || !(match_max_range_meters > 0.0) ||
      match_beam_step < 1) {
    *error = "need scans_per_submap >= 2, min_matched_points >= 0, match_max_range_meters > 0";
    return false;
  }
  return matcher.Validate(error) && refinement.Validate(error) && prior.Validate(error);
}

namespace {

constexpr double kVelocityMargin = 0.05;

bool Differs(const Pose2& a, const Pose2& b) {
  const Pose2 d = a.Between(b);
  return std::hypot(d.x, d.y) > 0.02 || std::abs(d.theta) > 0.02;
}

// Matches from the wheel odometry's prediction and, where it differs, from the constant-velocity
// prediction: logged odometry sometimes stalls for a few scans and then jumps to catch up.
// '*prediction' receives the prediction the better match started from.
MatchResult MatchBest(const LikelihoodField& field, const MatchPoints& points,
                      const Pose2& odometry_prediction, const Pose2& velocity_prediction,
                      const HillClimbingOptions& options, Pose2* prediction) {
  MatchResult best = HillClimb(field, points, odometry_prediction, options);
  *prediction = odometry_prediction;
  if (Differs(odometry_prediction, velocity_prediction)) {
    const MatchResult other = HillClimb(field, points, velocity_prediction, options);
    // The wheel odometry keeps the benefit of the doubt: where the scan barely constrains the
    // motion (a corridor) the two scores are nearly equal, and following the constant-velocity
    // guess there would freeze the estimate.
    if (other.evaluation.score > (1.0 + kVelocityMargin) * best.evaluation.score) {
      best = other;
      *prediction = velocity_prediction;
    }
  }
  return best;
}

}  // namespace

LaserOdometry::LaserOdometry(const LaserOdometryOptions& options,
                             const OccupancyGridOptions& grid_options,
                             const LikelihoodFieldOptions& field_options)
    : options_(options),
      grid_options_(grid_options),
      field_options_(field_options),
      prior_model_(options.prior) {}

Pose2 LaserOdometry::Add(const StampedScan& scan, const PreparedScan& prepared) {
  Pose2 pose = scan.odometry;
  if (!poses_.empty()) {
    const Pose2& last = poses_.back();
    pose = last * last_odometry_.Between(scan.odometry);
    const Pose2 velocity = poses_.size() >= 2 ? last * poses_.front().Between(last) : last;
    const LikelihoodField field(submaps_.front().grid, field_options_);
    // Hill climbing on every n-th return, the refinement on all of them.
    const MatchPoints sparse =
        SelectMatchPoints(prepared, options_.match_max_range_meters, options_.match_beam_step);
    Pose2 prediction;
    const MatchResult match =
        MatchBest(field, sparse, pose, velocity, options_.matcher, &prediction);
    const int available = sparse.measured * options_.match_beam_step;
    if (match.evaluation.matched * options_.match_beam_step >=
        RequiredMatches(options_.min_matched_points, available)) {
      pose = match.pose;
      if (options_.refinement.enabled) {
        const PosePrior prior{prediction, prior_model_.Sigmas(last.Between(prediction))};
        const MatchPoints all = SelectMatchPoints(prepared, options_.match_max_range_meters);
        pose = RefineOnSurface(field, all, match.pose, options_.refinement, &prior).pose;
      }
    } else {
      ++rejected_;
    }
  }
  if (poses_.size() == 2) poses_.erase(poses_.begin());
  poses_.push_back(pose);
  last_odometry_ = scan.odometry;
  // A new submap when the newest is half full; the oldest goes when it is full.
  if (submaps_.empty() || submaps_.back().scans >= options_.scans_per_submap / 2) {
    submaps_.push_back({OccupancyGrid(grid_options_), 0});
  }
  for (Submap& submap : submaps_) {
    InsertScan(prepared, pose, &submap.grid);
    ++submap.scans;
  }
  if (submaps_.front().scans >= options_.scans_per_submap) submaps_.pop_front();
  return pose;
}

std::vector<Pose2> ComputeLaserOdometry(const std::vector<StampedScan>& scans,
                                        const std::vector<PreparedScan>& prepared,
                                        const LaserOdometryOptions& options,
                                        const OccupancyGridOptions& grid_options,
                                        const LikelihoodFieldOptions& field_options,
                                        int* rejected) {
  SEMCHAIN_CHECK(scans.size() == prepared.size());
  LaserOdometry odometry(options, grid_options, field_options);
  std::vector<Pose2> poses;
  poses.reserve(scans.size());
  for (std::size_t i = 0; i < scans.size(); ++i)
    poses.push_back(odometry.Add(scans[i], prepared[i]));
  if (rejected != nullptr) *rejected = odometry.rejected();
  return poses;
}

}  // namespace semchain::mapping
