#pragma once

#include <nav_msgs/Odometry.h>
#include <ros/time.h>
#include <tf2/buffer_core.h>

#include <Eigen/Geometry>
#include <cstddef>
#include <memory>
#include <string>

#include "core/status.h"
#include "ros/bag_layout.h"
#include "ros/bag_reader.h"

// A bag's tf tree in a tf2 buffer that spans the whole bag, so that `bag import` can ask where
// the robot (and the laser, and the camera) was at any stamp: tf2 interpolates between the
// transforms recorded around it, exactly as a live node's tf listener would.
namespace semchain::ros1 {

// The tf frame id of a message header: 'frame_id' without the leading '/' of ROS's old style
// (tf2 drops it too), or 'fallback' when the header names none.
std::string TfFrameId(const std::string& frame_id, const std::string& fallback);

class BagTransforms {
 public:
  // Reads every message of 'topics.tf' and 'topics.tf_static' (static transforms hold at all
  // times). A bag without them gives an empty tree. The buffer spans the stamps of /tf and of
  // 'topics.odom', for AddOdometry.
  static Result<std::unique_ptr<BagTransforms>> Load(BagReader& reader, const BagTopics& topics);

  // Adds the robot's pose of every message of 'topic' (nav_msgs/Odometry, the 'odom' topic
  // given to Load) as the transform
  // 'odom_frame' → 'base_frame': odometry for bags that publish it on a topic but not on tf.
  Status AddOdometry(BagReader& reader, const std::string& topic, const std::string& odom_frame,
                     const std::string& base_frame);

  // Whether tf connects the two frames at some time.
  bool Connects(const std::string& target_frame, const std::string& source_frame) const;

  // The pose of 'source_frame' in 'target_frame' at 'time'; tf2's message when it cannot say
  // (frames not connected, 'time' outside the recorded span).
  Result<Eigen::Isometry3d> Lookup(const std::string& target_frame, const std::string& source_frame,
                                   const ros::Time& time) const;

  // The frames tf knows, "a, b, c", or "none".
  std::string Frames() const;
  // Transforms tf2 refused (no frame id, a frame its own parent, NaN).
  std::size_t rejected() const { return rejected_; }

 private:
  explicit BagTransforms(ros::Duration span) : buffer_(span) {}

  tf2::BufferCore buffer_;
  std::size_t rejected_ = 0;
};

}  // namespace semchain::ros1
