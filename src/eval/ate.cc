#include "eval/ate.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/angles.h"
#include "io/trajectory_lookup.h"

namespace semchain::eval {

Pose2 FitRigidTransform2D(const std::vector<Pose2>& from, const std::vector<Pose2>& to) {
  SEMCHAIN_CHECK(!from.empty() && from.size() == to.size());
  const double n = static_cast<double>(from.size());
  Eigen::Vector2d from_mean = Eigen::Vector2d::Zero(), to_mean = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < from.size(); ++i) {
    from_mean += from[i].translation() / n;
    to_mean += to[i].translation() / n;
  }
  // With p, q the centred points, the rotation angle maximising Σ q·(R p) is
  // atan2(Σ p × q, Σ p · q): the 2D case of Umeyama 1991, where the SVD reduces to an angle.
  double cross = 0.0, dot = 0.0;
  for (std::size_t i = 0; i < from.size(); ++i) {
    const Eigen::Vector2d p = from[i].translation() - from_mean;
    const Eigen::Vector2d q = to[i].translation() - to_mean;
    cross += p.x() * q.y() - p.y() * q.x();
    dot += p.dot(q);
  }
  const double angle = std::atan2(cross, dot);
  const Eigen::Vector2d rotated = Pose2(0.0, 0.0, angle) * from_mean;
  return Pose2(to_mean.x() - rotated.x(), to_mean.y() - rotated.y(), angle);
}

namespace {

Status CheckDistinctTimestamps(const std::vector<StampedPose>& truth) {
  std::vector<double> stamps;
  stamps.reserve(truth.size());
  for (const StampedPose& pose : truth) stamps.push_back(pose.timestamp);
  std::sort(stamps.begin(), stamps.end());
  const auto same = std::adjacent_find(stamps.begin(), stamps.end());
  if (same == stamps.end()) return Status::Ok();
  const auto count = std::count(stamps.begin(), stamps.end(), *same);
  std::ostringstream message;
  message << "the truth has " << count << " poses at time " << std::setprecision(12) << *same
          << " s: timestamps cannot pair the poses (pair them by index instead)";
  return Status::Error(message.str());
}

}  // namespace

Result<PairedPoses> PairWithTruth(const std::vector<StampedPose>& estimate,
                                  const std::vector<StampedPose>& truth,
                                  const AteOptions& options) {
  PairedPoses pairs;
  if (options.pair_by_index) {
    if (estimate.size() != truth.size()) {
      return Status::Error("pairing by index needs as many estimated poses as truth poses (" +
                           std::to_string(estimate.size()) + " vs " + std::to_string(truth.size()) +
                           ")");
    }
    for (std::size_t i = 0; i < estimate.size(); ++i) {
      pairs.estimated.push_back(estimate[i].pose);
      pairs.reference.push_back(truth[i].pose);
    }
  } else {
    SEMCHAIN_RETURN_IF_ERROR(CheckDistinctTimestamps(truth));
    const TrajectoryLookup lookup(truth);
    for (const StampedPose& pose : estimate) {
      const std::optional<Pose2> true_pose =
          lookup.At(pose.timestamp, options.timestamp_tolerance_s, options.max_interpolation_gap_s);
      if (!true_pose) continue;
      pairs.estimated.push_back(pose.pose);
      pairs.reference.push_back(*true_pose);
    }
  }
  if (pairs.estimated.empty()) {
    return Status::Error("none of the " + std::to_string(estimate.size()) +
                         " estimated poses has a truth pose at its time");
  }
  return pairs;
}

Result<AteResult> EvaluateAte(const std::vector<StampedPose>& estimate,
                              const std::vector<StampedPose>& truth, const AteOptions& options) {
  Result<PairedPoses> pairs = PairWithTruth(estimate, truth, options);
  if (!pairs.ok()) return pairs.status();
  const std::vector<Pose2>& estimated = pairs->estimated;
  const std::vector<Pose2>& reference = pairs->reference;
  AteResult result;
  result.poses = estimate.size();
  result.matched = estimated.size();
  if (options.align) result.alignment = FitRigidTransform2D(estimated, reference);
  double sum_sq = 0.0, sum = 0.0, sum_rot_sq = 0.0;
  for (std::size_t i = 0; i < estimated.size(); ++i) {
    const Pose2 aligned = result.alignment * estimated[i];
    const double error = (aligned.translation() - reference[i].translation()).norm();
    const double rot_deg = RadToDeg(AngleDifference(aligned.theta, reference[i].theta));
    sum += error;
    sum_sq += error * error;
    sum_rot_sq += rot_deg * rot_deg;
    result.ate_max_m = std::max(result.ate_max_m, error);
  }
  const double n = static_cast<double>(result.matched);
  result.ate_rmse_m = std::sqrt(sum_sq / n);
  result.ate_mean_m = sum / n;
  result.rot_rmse_deg = std::sqrt(sum_rot_sq / n);
  return result;
}

std::string AteResultToJson(const AteResult& r) {
  const nlohmann::ordered_json json = {
      {"poses", r.poses},           {"matched", r.matched},     {"ate_rmse_m", r.ate_rmse_m},
      {"ate_mean_m", r.ate_mean_m}, {"ate_max_m", r.ate_max_m}, {"rot_rmse_deg", r.rot_rmse_deg}};
  return json.dump(2);
}

}  // namespace semchain::eval
