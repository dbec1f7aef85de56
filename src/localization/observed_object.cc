#include "localization/observed_object.h"

#include <cmath>

#include "core/transforms.h"

namespace semchain::localization {

std::vector<ObservedObject> ObserveObjects(const std::vector<Detection>& detections,
                                           const MountedCamera& camera,
                                           const PreLocalizationOptions& options) {
  std::vector<ObservedObject> observed;
  const double right = camera.intrinsics.width - options.border_margin_px;
  for (std::size_t i = 0; i < detections.size(); ++i) {
    const Detection& d = detections[i];
    if (d.score < options.min_score || !(d.depth_m > 0.0)) continue;
    if (options.border_margin_px >= 0.0 &&
        (d.box[0] <= options.border_margin_px || d.box[2] >= right)) {
      continue;
    }
    // Box edges are pixel boundaries; pixel u covers [u − 0.5, u + 0.5).
    const double u = 0.5 * (d.box[0] + d.box[2]) - 0.5;
    const double v = 0.5 * (d.box[1] + d.box[3]) - 0.5;
    const Eigen::Vector3d robot =
        CameraToRobot(camera.robot_from_camera, camera.intrinsics.Backproject(u, v, d.depth_m));
    ObservedObject object;
    object.class_name = d.class_name;
    object.surface = robot.head<2>();
    object.range = object.surface.norm();
    object.bearing = std::atan2(object.surface.y(), object.surface.x());
    object.detection = static_cast<int>(i);
    observed.push_back(object);
  }
  return observed;
}

}  // namespace semchain::localization
