#include "localization/observation_memory.h"

#include <cmath>

#include "core/angles.h"
#include "core/check.h"

namespace semchain::localization {

bool ObservationMemoryOptions::Validate(std::string* error) const {
  if (!(max_rotation >= 0.0 && max_travel >= 0.0 && same_object_distance >= 0.0)) {
    *error = "observation memory: max_rotation, max_travel and same_object_distance must be >= 0";
    return false;
  }
  return true;
}

bool SameObject(const ObservedObject& a, const ObservedObject& b, double distance) {
  return a.class_name == b.class_name && (a.surface - b.surface).norm() < distance;
}

ObservationMemory::ObservationMemory(const ObservationMemoryOptions& options) : options_(options) {
  std::string error;
  SEMCHAIN_CHECK(options_.Validate(&error));
}

void ObservationMemory::Add(const Pose2& odometry, const std::vector<ObservedObject>& observed) {
  if (!frames_.empty()) {
    rotation_ += std::abs(NormalizeAngle(odometry.theta - last_odometry_.theta));
    travel_ += (odometry.translation() - last_odometry_.translation()).norm();
  }
  last_odometry_ = odometry;
  std::erase_if(frames_, [this](const Frame& f) {
    return rotation_ - f.rotation > options_.max_rotation ||
           travel_ - f.travel > options_.max_travel;
  });
  frames_.push_back({odometry, rotation_, travel_, observed});
}

std::vector<ObservedObject> ObservationMemory::Recall(const Pose2& odometry) const {
  std::vector<ObservedObject> recalled;
  if (frames_.empty()) return recalled;
  const double rotation =
      rotation_ + std::abs(NormalizeAngle(odometry.theta - last_odometry_.theta));
  const double travel = travel_ + (odometry.translation() - last_odometry_.translation()).norm();
  const Pose2 now_from_world = odometry.Inverse();
  for (int k = static_cast<int>(frames_.size()) - 1; k >= 0; --k) {
    const Frame& frame = frames_[static_cast<std::size_t>(k)];
    if (rotation - frame.rotation > options_.max_rotation ||
        travel - frame.travel > options_.max_travel) {
      continue;
    }
    const Pose2 now_from_then = now_from_world * frame.odometry;
    const std::size_t newer = recalled.size();  // objects of later frames end here
    for (const ObservedObject& seen : frame.observed) {
      ObservedObject moved = seen;
      moved.surface = now_from_then * seen.surface;
      moved.range = moved.surface.norm();
      moved.bearing = std::atan2(moved.surface.y(), moved.surface.x());
      moved.frames_ago = static_cast<int>(frames_.size()) - 1 - k;
      bool seen_later = false;
      for (std::size_t i = 0; i < newer && !seen_later; ++i) {
        seen_later = SameObject(recalled[i], moved, options_.same_object_distance);
      }
      if (!seen_later) recalled.push_back(moved);
    }
  }
  return recalled;
}

}  // namespace semchain::localization
