#include "eval/rpe.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/angles.h"
#include "eval/statistics.h"

namespace semchain::eval {
namespace {

RpeStretches StretchesOf(const std::vector<Pose2>& estimated, const std::vector<Pose2>& reference,
                         const std::vector<double>& travel, double length) {
  RpeStretches result;
  result.travel_m = length;
  std::vector<double> translation, rotation, along;
  std::size_t j = 0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    if (j < i) j = i;
    while (j < reference.size() && travel[j] - travel[i] < length) ++j;
    if (j == reference.size()) break;
    const Pose2 truth = reference[i].Between(reference[j]);
    const Pose2 estimate = estimated[i].Between(estimated[j]);
    const Pose2 error = truth.Between(estimate);
    translation.push_back(error.translation().norm());
    rotation.push_back(std::abs(RadToDeg(NormalizeAngle(error.theta))));
    const double true_length = truth.translation().norm();
    if (true_length > 0.0) {
      along.push_back(estimate.translation().dot(truth.translation()) / true_length - true_length);
    }
  }
  result.stretches = translation.size();
  if (translation.empty()) return result;
  result.translation_median_m = *Median(translation);
  result.translation_p95_m = Percentile(translation, 95.0);
  result.translation_max_m = Percentile(translation, 100.0);
  result.rotation_median_deg = *Median(rotation);
  result.rotation_p95_deg = Percentile(rotation, 95.0);
  result.rotation_max_deg = Percentile(rotation, 100.0);
  result.along_track_median_m = Median(along).value_or(0.0);
  return result;
}

}  // namespace

Result<RpeResult> EvaluateRpe(const std::vector<StampedPose>& estimate,
                              const std::vector<StampedPose>& truth, const RpeOptions& options) {
  for (const double length : options.travel_meters) {
    if (!(length > 0.0)) return Status::Error("stretch lengths must be > 0 metres");
  }
  Result<PairedPoses> pairs = PairWithTruth(estimate, truth, options.pairing);
  if (!pairs.ok()) return pairs.status();
  std::vector<double> travel = {0.0};
  for (std::size_t i = 1; i < pairs->reference.size(); ++i) {
    travel.push_back(
        travel.back() +
        (pairs->reference[i].translation() - pairs->reference[i - 1].translation()).norm());
  }
  RpeResult result;
  result.poses = estimate.size();
  result.matched = pairs->estimated.size();
  for (const double length : options.travel_meters) {
    result.stretches.push_back(StretchesOf(pairs->estimated, pairs->reference, travel, length));
  }
  return result;
}

std::string RpeResultToJson(const RpeResult& r) {
  nlohmann::ordered_json stretches = nlohmann::ordered_json::array();
  for (const RpeStretches& s : r.stretches) {
    stretches.push_back({{"travel_m", s.travel_m},
                         {"stretches", s.stretches},
                         {"translation_median_m", s.translation_median_m},
                         {"translation_p95_m", s.translation_p95_m},
                         {"translation_max_m", s.translation_max_m},
                         {"rotation_median_deg", s.rotation_median_deg},
                         {"rotation_p95_deg", s.rotation_p95_deg},
                         {"rotation_max_deg", s.rotation_max_deg},
                         {"along_track_median_m", s.along_track_median_m}});
  }
  const nlohmann::ordered_json json = {
      {"poses", r.poses}, {"matched", r.matched}, {"stretches", stretches}};
  return json.dump(2);
}

}  // namespace semchain::eval
