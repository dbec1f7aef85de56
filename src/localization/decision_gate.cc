#include "localization/decision_gate.h"

#include <algorithm>
#include <iterator>

#include "core/angles.h"

namespace semchain::localization {

bool DecisionGate::Update(const std::vector<PoseCandidate>& candidates, const Pose2& odometry,
                          int hidden_objects) {
  // Evidence noted at 'then' (odometry) is forgotten once the robot has moved far enough.
  const auto forgotten = [&](const Pose2& then) {
    return (then.translation() - odometry.translation()).norm() > options_.forget_after_travel;
  };
  if (tie_ && forgotten(tie_->second)) tie_.reset();
  if (poor_fit_ && forgotten(poor_fit_->place.odometry)) poor_fit_.reset();
  // No hypothesis: no pair of the objects seen fitted anywhere; nothing for or against.
  if (candidates.empty()) return false;
  const PoseCandidate& best = candidates.front();
  const int explained = best.agreeing + hidden_objects;
  if (!prelocalizer_.Decided(candidates)) {
    if (options_.new_evidence && (!tie_ || explained >= tie_->first)) {
      tie_.emplace(explained, odometry);
    }
    // A look-alike of the leader is as likely as it: the count starts again.
    leader_.reset();
    return false;
  }
  if (best.laser_score < options_.min_laser_score) {
    // The objects point to this place but the scan, refined there, disagrees with the map: the
    // place is wrong or placed too far off for the laser to reach it. Either way it decides
    // nothing, and no place elsewhere explaining fewer objects may be decided over it.
    if (!poor_fit_ || explained >= poor_fit_->explained) {
      poor_fit_ = PoorFit{{best.pose, odometry}, explained};
    }
    return false;
  }
  if (tie_ && explained <= tie_->first) return false;
  if (poor_fit_ && explained < poor_fit_->explained &&
      prelocalizer_.DistinctPlaces(poor_fit_->place.At(odometry), best.pose)) {
    return false;
  }
  // The leader's place carried by odometry to where this pre-localization was made.
  const bool at_leader =
      leader_ && !prelocalizer_.DistinctPlaces(leader_->place.At(odometry), best.pose);
  std::vector<int> objects;
  for (const auto& [observed, id] : best.matches) objects.push_back(id);
  std::sort(objects.begin(), objects.end());
  if (at_leader) {
    std::vector<int> seen;
    std::set_union(objects.begin(), objects.end(), leader_->objects.begin(), leader_->objects.end(),
                   std::back_inserter(seen));
    const bool new_object = seen.size() > leader_->objects.size();
    const bool new_view = std::abs(NormalizeAngle(odometry.theta - leader_->counted_heading)) >=
                          options_.confirmation_turn;
    const bool counts = new_object || new_view;
    leader_ = Leader{.place = {best.pose, odometry},
                     .explained = explained,
                     .laser_score = best.laser_score,
                     .count = leader_->count + (counts ? 1 : 0),
                     .objects = std::move(seen),
                     .counted_heading = counts ? odometry.theta : leader_->counted_heading};
  } else if (!leader_ || explained > leader_->explained ||
             (explained == leader_->explained && best.laser_score > leader_->laser_score)) {
    leader_ = Leader{.place = {best.pose, odometry},
                     .explained = explained,
                     .laser_score = best.laser_score,
                     .count = 1,
                     .objects = std::move(objects),
                     .counted_heading = odometry.theta};
  } else {
    // A lone place the objects and the laser support less than the leader: a frame that left
    // the leader out (its pair placed too far off), not evidence against it.
    return false;
  }
  return leader_->count >= options_.confirmations;
}

void DecisionGate::Reset() {
  leader_.reset();
  tie_.reset();
  poor_fit_.reset();
}

}  // namespace semchain::localization
