#pragma once

#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/LaserScan.h>
#include <std_msgs/String.h>
#include <std_srvs/Empty.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/status.h"
#include "detection/yolo_detector.h"
#include "localization/localizer.h"
#include "ros/node_inputs.h"
#include "ros/node_parameters.h"

// semchain_ros in localization mode: a drop-in for ROS amcl that runs a semchain Localizer.
//   subscribes  /scan, tf odom → base_link (laser and camera frames from tf), /initialpose,
//               /semchain/detections (one detections.jsonl record per message) or, with
//               ~detector, /camera/color/image_raw + /camera/depth/image_raw (aligned to colour);
//               /camera/color/camera_info for the camera's intrinsics and frame
//   publishes   /amcl_pose, /particlecloud, tf map → odom, latched /map and /semchain/objects
//   offers      /global_localization (std_srvs/Empty)
namespace semchain::ros1 {

// CPU per scan and latency from a scan's arrival to its published pose.
struct NodeTimings {
  std::vector<double> cpu_ms;      // the localizer's thread CPU per processed scan
  std::vector<double> latency_ms;  // wall time from the scan callback's entry to the publish
  // The part of it after odometry (tf odom → base_link at the scan's stamp) was known: the
  // rest is waiting for tf, which a bag or a driver publishes after the scan.
  std::vector<double> processing_ms;
  int dropped_scans = 0;  // no odometry (tf) for them in time
};

class LocalizationNode {
 public:
  // Loads the map folder, the detector and the vocabulary the parameters name; an error says
  // which file or parameter is wrong.
  static Result<std::unique_ptr<LocalizationNode>> Create(::ros::NodeHandle nh,
                                                          ::ros::NodeHandle private_nh);
  ~LocalizationNode();
  LocalizationNode(const LocalizationNode&) = delete;
  LocalizationNode& operator=(const LocalizationNode&) = delete;

  const NodeTimings& timings() const { return timings_; }
  // Writes ~stats_file (when set): scans, CPU and latency (mean, median, p95, max).
  Status WriteStats() const;

 private:
  LocalizationNode(::ros::NodeHandle nh, ::ros::NodeHandle private_nh,
                   LocalizationNodeParameters parameters,
                   std::unique_ptr<localization::LocalizerMap> map,
                   std::unique_ptr<detection::YoloDetector> detector);
  void Start();

  void OnScan(const sensor_msgs::LaserScanConstPtr& message);
  void OnDetections(const std_msgs::StringConstPtr& message);
  void OnCameraInfo(const sensor_msgs::CameraInfoConstPtr& message);
  void OnColorImage(const sensor_msgs::ImageConstPtr& message);
  void OnDepthImage(const sensor_msgs::ImageConstPtr& message);
  void OnInitialPose(const geometry_msgs::PoseWithCovarianceStampedConstPtr& message);
  bool OnGlobalLocalization(std_srvs::Empty::Request& request, std_srvs::Empty::Response& response);

  void AddFrame(double stamp, std::vector<Detection> detections, const cv::Mat& color);
  void Publish(const ::ros::Time& stamp, const Pose2& odometry, bool filter_updated);
  void PublishObjects();
  void NoteState();

  ::ros::NodeHandle nh_;
  ::ros::NodeHandle private_nh_;
  const LocalizationNodeParameters parameters_;
  std::unique_ptr<localization::LocalizerMap> map_;
  std::unique_ptr<detection::YoloDetector> detector_;
  localization::Localizer localizer_;

  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;

  ::ros::Subscriber scan_subscriber_;
  ::ros::Subscriber detections_subscriber_;
  ::ros::Subscriber camera_info_subscriber_;
  ::ros::Subscriber color_subscriber_;
  ::ros::Subscriber depth_subscriber_;
  ::ros::Subscriber initial_pose_subscriber_;
  ::ros::Publisher pose_publisher_;
  ::ros::Publisher particles_publisher_;
  ::ros::Publisher map_publisher_;
  ::ros::Publisher objects_publisher_;
  ::ros::ServiceServer global_localization_service_;

  CameraTracker camera_;
  RgbdDetector rgbd_;
  std::optional<geometry_msgs::TransformStamped> map_from_odom_;
  localization::LocalizerState last_state_ = localization::LocalizerState::kLost;
  std::size_t published_hypotheses_ = 0;
  NodeTimings timings_;
};

}  // namespace semchain::ros1
