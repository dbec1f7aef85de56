#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "localization/prelocalization_options.h"
#include "sensors/camera.h"
#include "sensors/detection.h"

namespace semchain::localization {

// An object seen in a frame, in the robot frame: where the camera saw its surface (the box
// centre's pixel at the detection's depth), and the bearing and range of that point.
struct ObservedObject {
  std::string class_name;
  Eigen::Vector2d surface = Eigen::Vector2d::Zero();  // robot frame, metres
  double range = 0.0;
  double bearing = 0.0;
  int detection = -1;  // index in the frame's detections
  int frames_ago = 0;  // 0: the current frame (see ObservationMemory)
};

// The usable detections of a frame (score, depth, not cut off by the image's sides; see
// PreLocalizationOptions) as observed objects.
std::vector<ObservedObject> ObserveObjects(const std::vector<Detection>& detections,
                                           const MountedCamera& camera,
                                           const PreLocalizationOptions& options);

}  // namespace semchain::localization
