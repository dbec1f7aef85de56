#pragma once

#include <string>

// The topics and tf frames of a semchain bag (DESIGN.md §5.7): what `semchain bag export`
// writes, what `semchain bag import` reads by default, and what the ROS node subscribes to.
//   /scan                      sensor_msgs/LaserScan, frame 'laser'
//   /tf                        tf2_msgs/TFMessage: odom → base_link at every scan
//   /tf_static                 (latched) base_link → laser, base_link → camera optical frame
//   /odom                      nav_msgs/Odometry: the same odometry with its velocities
//   /camera/color/image_raw    sensor_msgs/Image rgb8
//   /camera/depth/image_raw    sensor_msgs/Image 16UC1 (mm) or 32FC1 (m), aligned to colour
//   /camera/color/camera_info  sensor_msgs/CameraInfo
//   /semchain/detections       std_msgs/String: one detections.jsonl record per frame (§5.5)
//   /semchain/truth            geometry_msgs/PoseStamped, frame 'map': the simulator's truth
//   /semchain/run_info         (latched) std_msgs/String: what no ROS message carries (run_info.h)
namespace semchain::ros1 {

struct BagTopics {
  std::string scan = "/scan";
  std::string tf = "/tf";
  std::string tf_static = "/tf_static";
  std::string odom = "/odom";
  // The RGB-D camera's namespace: <camera>/color/image_raw, <camera>/color/camera_info and
  // <camera>/depth/image_raw, as `bag export` writes them. `bag import` also finds other
  // layouts in it and compressed images (camera_topics.h), unless 'color_image', 'depth_image'
  // or 'camera_info' name the topic (e.g. a RealSense's /camera/aligned_depth_to_color/image_raw).
  std::string camera = "/camera";
  std::string color_image;
  std::string depth_image;
  std::string camera_info;
  std::string detections = "/semchain/detections";
  std::string truth = "/semchain/truth";
  std::string run_info = "/semchain/run_info";

  std::string ColorImage() const {
    return color_image.empty() ? camera + "/color/image_raw" : color_image;
  }
  std::string CameraInfo() const {
    return camera_info.empty() ? camera + "/color/camera_info" : camera_info;
  }
  std::string DepthImage() const {
    return depth_image.empty() ? camera + "/depth/image_raw" : depth_image;
  }
};

// tf frame ids (REP 105 names).
struct BagFrames {
  std::string map = "map";
  std::string odom = "odom";
  std::string base = "base_link";
  std::string laser = "laser";
  std::string camera = "camera_color_optical_frame";
};

}  // namespace semchain::ros1
