#include "localization/decision_gate.h"

namespace semchain::localization {

bool DecisionGate::Update(const std::vector<PoseCandidate>& candidates, const Pose2& odometry,
                          int hidden_objects) {
  if (tie_ &&
      (tie_->second.translation() - odometry.translation()).norm() > options_.forget_after_travel) {
    tie_.reset();
  }
  bool decided = prelocalizer_.Decided(candidates);
  const int explained = candidates.empty() ? 0 : candidates.front().agreeing + hidden_objects;
  if (!decided && !candidates.empty() && options_.new_evidence &&
      (!tie_ || explained >= tie_->first)) {
    tie_.emplace(explained, odometry);
  }
  if (decided && tie_ && explained <= tie_->first) decided = false;
  if (!decided) {
    decision_.reset();
    streak_ = 0;
    return false;
  }
  const Pose2& best = candidates.front().pose;
  const bool same_place =
      decision_ &&
      !prelocalizer_.DistinctPlaces(decision_->first * decision_->second.Between(odometry), best);
  streak_ = same_place ? streak_ + 1 : 1;
  decision_.emplace(best, odometry);
  return streak_ >= options_.confirmations;
}

void DecisionGate::Reset() {
  decision_.reset();
  streak_ = 0;
  tie_.reset();
}

}  // namespace semchain::localization
