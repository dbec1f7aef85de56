#pragma once

#include <ros/node_handle.h>

#include <string>

#include "core/status.h"
#include "ros/node_inputs.h"

// Reading the node's private parameters: an unset parameter keeps the value already there (the
// documented default); one of the wrong type is an error naming it, never a silent default.
namespace semchain::ros1 {

template <typename T>
Status ReadParameter(const ::ros::NodeHandle& nh, const std::string& name, T* value) {
  if (!nh.hasParam(name)) return Status::Ok();
  if (!nh.getParam(name, *value)) return Status::Error("parameter ~" + name + ": wrong type");
  return Status::Ok();
}

// A double that may also be written as an integer (ROS parameters "1" vs "1.0").
Status ReadDoubleParameter(const ::ros::NodeHandle& nh, const std::string& name, double* value);

// ~base_frame_id, ~odom_frame_id, ~global_frame_id (or 'global_name', e.g. slam_gmapping's
// map_frame), ~tf_wait.
Status ReadNodeFrames(const ::ros::NodeHandle& nh, NodeFrames* frames,
                      const std::string& global_name = "global_frame_id");

}  // namespace semchain::ros1
