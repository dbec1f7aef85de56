#pragma once

#include <string>
#include <vector>

#include "core/pose2.h"
#include "localization/observed_object.h"

// The objects seen over the last frames, carried into the current robot frame by odometry.
// A robot that turns in place to relocalize sees its surroundings one camera field of view at a
// time: two objects on opposite sides (the only two in a corridor, or a door behind it) are never
// in one frame, but both are seen within one turn, and odometry over a turn in place is good to a
// few degrees. Pre-localization then works on everything seen during the turn, not on one frame.
namespace semchain::localization {

struct ObservationMemoryOptions {
  // An observation is forgotten once the robot has turned more than this (radians) or driven
  // more than this (metres) since it was made: by then odometry error has grown, and after a full
  // turn the object is seen again anyway.
  double max_rotation = 2.0 * 3.14159265358979323846;
  double max_travel = 1.0;
  // An object seen in an earlier frame is the one seen later when it lies within this distance
  // (metres, in the current frame) of a later observation of its class: only the later is kept.
  double same_object_distance = 0.3;

  bool Validate(std::string* error) const;
};

// Whether two sightings, in one frame, are of one object: the same class within 'distance'.
bool SameObject(const ObservedObject& a, const ObservedObject& b, double distance);

class ObservationMemory {
 public:
  explicit ObservationMemory(const ObservationMemoryOptions& options = {});

  // Adds a frame's objects (robot frame at 'odometry'). Frames come in time order.
  void Add(const Pose2& odometry, const std::vector<ObservedObject>& observed);

  // Everything remembered, in the robot frame at 'odometry' (the latest pose), newest frame first;
  // 'detection' indices refer to each object's own frame, 'frames_ago' says which.
  std::vector<ObservedObject> Recall(const Pose2& odometry) const;

  void Clear() { frames_.clear(); }

 private:
  struct Frame {
    Pose2 odometry;
    double rotation = 0.0;  // cumulative |Δθ| and distance driven when it was taken
    double travel = 0.0;
    std::vector<ObservedObject> observed;
  };

  ObservationMemoryOptions options_;
  std::vector<Frame> frames_;  // oldest first
  Pose2 last_odometry_;
  double rotation_ = 0.0;
  double travel_ = 0.0;
};

}  // namespace semchain::localization
