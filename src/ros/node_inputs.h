#pragma once

#include <geometry_msgs/TransformStamped.h>
#include <ros/time.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_ros/buffer.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/status.h"
#include "detection/yolo_detector.h"
#include "sensors/camera.h"
#include "sensors/detection.h"
#include "sensors/laser_scan.h"

// What both modes of semchain_ros take in the same way: transforms from tf, scans with their
// odometry, the camera from camera_info and tf, and detections from RGB-D images.
namespace semchain::ros1 {

// The frames the node reads from tf (ROS amcl's and slam_gmapping's parameter names).
struct NodeFrames {
  std::string base_frame_id = "base_link";
  std::string odom_frame_id = "odom";
  std::string global_frame_id = "map";
  double tf_wait = 0.5;  // ~tf_wait: s a scan waits for odom → base_link
};

// target_from_source at 'stamp' (waiting up to 'wait' seconds); unknown: a throttled warning.
std::optional<geometry_msgs::TransformStamped> LookUpTransform(const tf2_ros::Buffer& buffer,
                                                               const std::string& target,
                                                               const std::string& source,
                                                               const ::ros::Time& stamp,
                                                               double wait);

// 'message' with the odometry (tf odom → base_link at its stamp) and the laser's mounting
// (base → the scan's frame, static); nullopt when tf does not know them in time.
std::optional<StampedScan> ScanWithOdometry(const tf2_ros::Buffer& buffer,
                                            const sensor_msgs::LaserScan& message,
                                            const NodeFrames& frames);

// The camera from /camera/color/camera_info and tf, once both are known.
class CameraTracker {
 public:
  explicit CameraTracker(double max_range) : max_range_(max_range) {}
  void OnCameraInfo(const sensor_msgs::CameraInfo& message);
  // The camera (intrinsics and its mounting on 'base_frame'); nullopt with a throttled warning
  // while camera_info or the transform is missing.
  std::optional<MountedCamera> Camera(const tf2_ros::Buffer& buffer, const NodeFrames& frames);

 private:
  double max_range_;
  std::optional<sensor_msgs::CameraInfo> info_;
  std::optional<MountedCamera> camera_;
};

// A colour image's detections by ~detector, with the aligned depth image of the same moment.
struct RgbdDetections {
  double stamp = 0.0;
  std::vector<Detection> detections;
  cv::Mat color;    // RGB
  cv::Mat depth_m;  // CV_32FC1, metres (0: no reading)
};

// Pairs /camera/color/image_raw with /camera/depth/image_raw and runs the detector on it.
class RgbdDetector {
 public:
  explicit RgbdDetector(detection::YoloDetector* detector) : detector_(detector) {}
  void OnDepthImage(const sensor_msgs::ImageConstPtr& message) { latest_depth_ = message; }
  // The frame's detections; nullopt with a throttled warning when it cannot be used.
  std::optional<RgbdDetections> OnColorImage(const sensor_msgs::Image& message);

 private:
  detection::YoloDetector* detector_;
  sensor_msgs::ImageConstPtr latest_depth_;
};

// ~detector's model (no detector, null, when 'model' is empty); the error names the file.
Result<std::unique_ptr<detection::YoloDetector>> LoadNodeDetector(const std::string& model);

// Mean, median, 95th percentile and maximum of 'values' as JSON (null when empty).
nlohmann::json Spread(std::vector<double> values);

}  // namespace semchain::ros1
