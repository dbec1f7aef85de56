#include "mapping/slam_options.h"

namespace semchain::mapping {

bool SlamOptions::Validate(std::string* error) const {
  if (!rbpf.Validate(error)) return false;
  if (!laser_odometry.Validate(error)) {
    *error = "laser_odometry." + *error;
    return false;
  }
  if (!loop_closure.Validate(error)) {
    *error = "pose_graph." + *error;
    return false;
  }
  if (every_scan.Validate(error)) return true;
  *error = "every_scan." + *error;
  return false;
}

}  // namespace semchain::mapping
