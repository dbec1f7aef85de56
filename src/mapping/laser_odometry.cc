#include "mapping/laser_odometry.h"

#include <cmath>
#include <deque>

#include "core/check.h"
#include "mapping/ray_casting.h"

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

struct Submap {
  OccupancyGrid grid;
  int scans = 0;
};

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

std::vector<Pose2> ComputeLaserOdometry(const std::vector<StampedScan>& scans,
                                        const std::vector<PreparedScan>& prepared,
                                        const LaserOdometryOptions& options,
                                        const OccupancyGridOptions& grid_options,
                                        const LikelihoodFieldOptions& field_options,
                                        int* rejected) {
  SEMCHAIN_CHECK(scans.size() == prepared.size());
  std::vector<Pose2> poses;
  poses.reserve(scans.size());
  std::deque<Submap> submaps;
  int rejections = 0;
  const MotionModel prior_model(options.prior);
  for (std::size_t i = 0; i < scans.size(); ++i) {
    Pose2 pose = scans[i].odometry;
    if (i > 0) {
      pose = poses.back() * scans[i - 1].odometry.Between(scans[i].odometry);
      const Pose2 velocity =
          i >= 2 ? poses.back() * poses[i - 2].Between(poses.back()) : poses.back();
      const LikelihoodField field(submaps.front().grid, field_options);
      // Hill climbing on every n-th return, the refinement on all of them.
      const MatchPoints sparse =
          SelectMatchPoints(prepared[i], options.match_max_range_meters, options.match_beam_step);
      Pose2 prediction;
      const MatchResult match =
          MatchBest(field, sparse, pose, velocity, options.matcher, &prediction);
      if (match.evaluation.matched * options.match_beam_step >= options.min_matched_points) {
        pose = match.pose;
        if (options.refinement.enabled) {
          const PosePrior prior{prediction, prior_model.Sigmas(poses.back().Between(prediction))};
          const MatchPoints all = SelectMatchPoints(prepared[i], options.match_max_range_meters);
          pose = RefineOnSurface(field, all, match.pose, options.refinement, &prior).pose;
        }
      } else {
        ++rejections;
      }
    }
    poses.push_back(pose);
    // A new submap when the newest is half full; the oldest goes when it is full.
    if (submaps.empty() || submaps.back().scans >= options.scans_per_submap / 2) {
      submaps.push_back({OccupancyGrid(grid_options), 0});
    }
    for (Submap& submap : submaps) {
      InsertScan(prepared[i], pose, &submap.grid);
      ++submap.scans;
    }
    if (submaps.front().scans >= options.scans_per_submap) submaps.pop_front();
  }
  if (rejected != nullptr) *rejected = rejections;
  return poses;
}

}  // namespace semchain::mapping
