#include "localization/decision_gate.h"

namespace semchain::localization {

bool DecisionGate::Update(const std::vector<PoseCandidate>& candidates, const Pose2& odometry,
                          int hidden_objects) {
  // Evidence noted at 'then' (odometry) is forgotten once the robot has moved far enough.
  const auto forgotten = [&](const Pose2& then) {
    return (then.translation() - odometry.translation()).norm() > options_.forget_after_travel;
  };
  if (tie_ && forgotten(tie_->second)) tie_.reset();
  if (poor_fit_ && forgotten(poor_fit_->odometry)) poor_fit_.reset();
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
      poor_fit_ = PoorFit{best.pose, odometry, explained};
    }
    return false;
  }
  if (tie_ && explained <= tie_->first) return false;
  if (poor_fit_ && explained < poor_fit_->explained &&
      prelocalizer_.DistinctPlaces(poor_fit_->pose * poor_fit_->odometry.Between(odometry),
                                   best.pose)) {
    return false;
  }
  // The leader's place carried by odometry to where this pre-localization was made.
  const bool at_leader =
      leader_ &&
      !prelocalizer_.DistinctPlaces(leader_->pose * leader_->odometry.Between(odometry), best.pose);
  if (at_leader) {
    const int count = leader_->count + 1;
    leader_ = Leader{best.pose, odometry, explained, best.laser_score, count};
  } else if (!leader_ || explained > leader_->explained ||
             (explained == leader_->explained && best.laser_score > leader_->laser_score)) {
    leader_ = Leader{best.pose, odometry, explained, best.laser_score, 1};
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
