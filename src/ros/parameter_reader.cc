#include "ros/parameter_reader.h"

namespace semchain::ros1 {

Status ReadDoubleParameter(const ::ros::NodeHandle& nh, const std::string& name, double* value) {
  if (!nh.hasParam(name)) return Status::Ok();
  if (nh.getParam(name, *value)) return Status::Ok();
  int integer = 0;
  if (nh.getParam(name, integer)) {
    *value = integer;
    return Status::Ok();
  }
  return Status::Error("parameter ~" + name + ": expected a number");
}

Status ReadNodeFrames(const ::ros::NodeHandle& nh, NodeFrames* frames,
                      const std::string& global_name) {
  SEMCHAIN_RETURN_IF_ERROR(ReadParameter(nh, "base_frame_id", &frames->base_frame_id));
  SEMCHAIN_RETURN_IF_ERROR(ReadParameter(nh, "odom_frame_id", &frames->odom_frame_id));
  SEMCHAIN_RETURN_IF_ERROR(ReadParameter(nh, global_name, &frames->global_frame_id));
  SEMCHAIN_RETURN_IF_ERROR(ReadDoubleParameter(nh, "tf_wait", &frames->tf_wait));
  if (!(frames->tf_wait >= 0.0)) return Status::Error("parameter ~tf_wait: must be >= 0");
  return Status::Ok();
}

}  // namespace semchain::ros1
