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
#include <mutex>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/status.h"
#include "detection/yolo_detector.h"
#include "localization/localizer.h"
#include "ros/detector_thread.h"
#include "ros/node_inputs.h"
#include "ros/node_mode.h"
#include "ros/node_parameters.h"
#include "ros/scan_input.h"

// semchain_ros in localization mode: a drop-in for ROS amcl that runs a semchain Localizer.
//   subscribes  /scan, tf odom → base_link (laser and camera frames from tf), /initialpose,
//               /semchain/detections (one detections.jsonl record per message) or, with
//               ~detector, /camera/color/image_raw + /camera/depth/image_raw (aligned to colour;
//               the detector runs on a thread of its own, DetectorThread, so that scans never
//               wait for it); /camera/color/camera_info for the camera's intrinsics and frame
//   publishes   /amcl_pose (on filter updates, as amcl; ~publish_pose_every_scan: after every
//               scan), /particlecloud, tf map → odom, latched /map and /semchain/objects
//   offers      /global_localization (std_srvs/Empty)
namespace semchain::ros1 {

// CPU per scan and latency from a scan's arrival to its published pose.
struct NodeTimings {
  std::vector<double> cpu_ms;  // the localizer's thread CPU per processed scan
  // Wall time from the scan's arrival (its subscriber's callback) to the scan's outputs
  // published (tf map → odom, and /amcl_pose when it was published).
  std::vector<double> latency_ms;
  // The same for the scans whose /amcl_pose was published.
  std::vector<double> pose_latency_ms;
  // From the arrival until the tf filter released the scan (odom → base_link at its stamp
  // known: a bag or a driver publishes tf just after the scan) ...
  std::vector<double> tf_wait_ms;
  // ... and from then on to the outputs published.
  std::vector<double> processing_ms;
  int dropped_scans = 0;    // odometry (tf) never came for them
  int scans_with_pose = 0;  // processed scans after which the localizer had a pose
  int poses_published = 0;  // /amcl_pose messages
};

class LocalizationNode {
 public:
  // Loads the map folder, the detector and the vocabulary the parameters name; an error says
  // which file or parameter is wrong.
  // 'mode' is for the start-up line.
  static Result<std::unique_ptr<LocalizationNode>> Create(::ros::NodeHandle nh,
                                                          ::ros::NodeHandle private_nh,
                                                          const NodeMode& mode);
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
  void Start(const NodeMode& mode);

  void OnScan(const sensor_msgs::LaserScanConstPtr& message, const ScanArrival& arrival);
  void OnDetections(const std_msgs::StringConstPtr& message);
  void OnCameraInfo(const sensor_msgs::CameraInfoConstPtr& message);
  void OnColorImage(const sensor_msgs::ImageConstPtr& message);
  void OnDepthImage(const sensor_msgs::ImageConstPtr& message);
  void OnInitialPose(const geometry_msgs::PoseWithCovarianceStampedConstPtr& message);
  bool OnGlobalLocalization(std_srvs::Empty::Request& request, std_srvs::Empty::Response& response);

  // Gives the localizer a frame (on the thread of its source: the detector's or the main one).
  void AddFrame(double stamp, std::vector<Detection> detections, const cv::Mat& color);
  // Publishes the scan's outputs; returns whether /amcl_pose was published.
  bool Publish(const ::ros::Time& stamp, const Pose2& odometry, bool filter_updated);
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

  // With ~detector: the camera's subscriptions are served here (declared before them, so that
  // it outlives them; stopped first thing in the destructor).
  std::unique_ptr<DetectorThread> detector_thread_;
  std::unique_ptr<ScanInput> scan_input_;
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

  // Used on the thread of the frames' source only (camera_info comes on the same queue).
  CameraTracker camera_;
  RgbdDetector rgbd_;
  // Guards the localizer and what goes with it (below) between the main queue's callbacks and
  // the detector's thread, which only hands over frames (Localizer::AddFrame queues them).
  std::mutex mutex_;
  std::optional<geometry_msgs::TransformStamped> map_from_odom_;
  localization::LocalizerState last_state_ = localization::LocalizerState::kLost;
  std::size_t published_hypotheses_ = 0;
  // The next scan's pose is published even without a filter update (as amcl's
  // force_publication): the first pose, after /initialpose, /global_localization or a change of
  // the localizer's state.
  bool force_pose_ = true;
  NodeTimings timings_;
};

}  // namespace semchain::ros1
