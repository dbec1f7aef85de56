#pragma once

#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/LaserScan.h>
#include <std_msgs/String.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

#include "core/status.h"
#include "detection/yolo_detector.h"
#include "mapping/incremental_slam.h"
#include "ros/detector_thread.h"
#include "ros/mapping_parameters.h"
#include "ros/node_inputs.h"
#include "ros/node_mode.h"
#include "ros/scan_input.h"
#include "semantic/keyframe_images.h"
#include "semantic/live_semantic_run.h"

// semchain_ros in mapping mode (~mode:=mapping): a drop-in for slam_gmapping that also maps
// semantics. `semchain slam`'s SLAM (laser-odometry front end + RBPF) fed scan by scan, and the
// semantic mapper fed the camera frames and SLAM's best trajectory as they arrive.
//   subscribes  /scan, tf odom → base_link (laser and camera frames from tf),
//               /camera/color/camera_info, /semchain/detections (one detections.jsonl record
//               per message) or, with ~detector, /camera/color/image_raw + /camera/depth/image_raw
//               (the detector and the semantic mapper run on a thread of their own,
//               DetectorThread: scans never wait for them; frames reach the mapper in stamp order)
//   publishes   latched /map every ~map_update_interval s of scan time, tf map → odom (the best
//               particle's pose ∘ odometry⁻¹) after every scan, /semchain/objects with /map
//   offers      /semchain/save_map (std_srvs/Trigger): the map folder to ~out, atomically; the
//               node also saves there when it stops (~save_on_shutdown)
namespace semchain::ros1 {

struct MappingTimings {
  std::vector<double> cpu_ms;     // thread CPU per scan: SLAM (and the semantic mapper when no
                                  // ~detector: it then runs on the scans' thread)
  std::vector<double> detect_ms;  // wall time of ~detector per camera frame
  double semantic_seconds = 0.0;  // thread CPU of the semantic mapper advancing on the trajectory
  double snapshot_seconds = 0.0;  // thread CPU of the objects' snapshots for /semchain/objects
  int dropped_scans = 0;          // no odometry (tf) for them
  int rejected_scans = 0;         // out of time order, or repeated
  double first_stamp = -1.0;      // scan time span, for the real-time factor
  double last_stamp = -1.0;
  double wall_seconds = 0.0;  // wall time from the first scan to the last
};

class MappingNode {
 public:
  // Reads the parameters and loads the detector; an error names the parameter or file.
  // 'mode' is for the start-up line.
  static Result<std::unique_ptr<MappingNode>> Create(::ros::NodeHandle nh,
                                                     ::ros::NodeHandle private_nh,
                                                     const NodeMode& mode);
  ~MappingNode();
  MappingNode(const MappingNode&) = delete;
  MappingNode& operator=(const MappingNode&) = delete;

  // Writes the map folder to ~out (the final SLAM passes, the semantic map on them); nothing
  // is written when there is no scan yet or on error (the error says why). Frames the detector
  // has not handed over yet are not in it (the save service waits for them first).
  Status Save();
  // What the node does when it stops: saves (~save_on_shutdown) and writes ~stats_file.
  void Shutdown();

 private:
  MappingNode(::ros::NodeHandle nh, MappingNodeParameters parameters,
              std::unique_ptr<detection::YoloDetector> detector);
  void Start(const NodeMode& mode);

  void OnScan(const sensor_msgs::LaserScanConstPtr& message);
  void OnDetections(const std_msgs::StringConstPtr& message);
  void OnCameraInfo(const sensor_msgs::CameraInfoConstPtr& message);
  void OnColorImage(const sensor_msgs::ImageConstPtr& message);
  // The colour image kept for the keyframes when /semchain/detections feeds the mapper.
  void OnKeyframeImage(const sensor_msgs::ImageConstPtr& message);
  void OnDepthImage(const sensor_msgs::ImageConstPtr& message);
  bool OnSaveMap(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);

  // Whether 'scan' can follow the scans before it (newer than the last; any beam geometry);
  // warns when not.
  bool Acceptable(const StampedScan& scan) const;
  void Feed(const StampedScan& scan);
  // Maps the frames the trajectory now poses ('corrected': SLAM's filter has updated, mapped
  // frames may move); on the frames' thread (the detector's or the main one), with mutex_ held.
  void AdvanceSemantic(bool corrected);
  std::vector<StampedPose> Trajectory() const;  // a copy, under trajectory_mutex_
  // Gives the semantic mapper a frame (on the thread of its source: the detector's or the main
  // one).
  void AddFrame(FrameDetections frame, const cv::Mat& depth_m);
  void AddDetectedFrame(std::optional<RgbdDetections> detected);
  // Gives the semantic mapper the frames that waited for the camera (created with the first);
  // with mutex_ held.
  void MapAwaitingFrames(const MountedCamera& camera);
  void PublishTransform(const ::ros::Time& stamp, const Pose2& pose, const Pose2& odometry);
  // /map from SLAM's best particle, and the objects on it (PublishObjects: on the detector's
  // thread when there is one).
  void PublishMap(const ::ros::Time& stamp);
  void PublishObjects(const mapping::MapImage& image, const ::ros::Time& stamp);
  int MappedFrames() const;  // with mutex_ held (or the detector's thread stopped)
  Status WriteStats() const;

  ::ros::NodeHandle nh_;
  const MappingNodeParameters parameters_;
  std::unique_ptr<detection::YoloDetector> detector_;
  mapping::IncrementalSlam slam_;

  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  // Used on the thread of the frames' source only (camera_info comes on the same queue).
  CameraTracker camera_;
  RgbdDetector rgbd_;
  // Guards what the detector's thread shares with the main queue's callbacks: the semantic
  // mapper and the frames on their way to it, the keyframes' images and the detector's timings.
  // SLAM is the main queue's alone.
  std::mutex mutex_;
  std::unique_ptr<semantic::LiveSemanticRun> semantic_;  // once the camera is known
  semantic::KeyframeImages keyframe_images_;
  // Frames on their way to the semantic mapper, waiting while the camera is not known yet (at
  // most the frames' queue); those dropped from a full queue are counted.
  struct AwaitingFrame {
    FrameDetections frame;
    cv::Mat depth_m;
  };
  std::deque<AwaitingFrame> frames_awaiting_camera_;
  int frames_lost_ = 0;

  // With ~detector: the camera's subscriptions are served here (declared before them, so that
  // it outlives them; stopped first thing when the node shuts down).
  std::unique_ptr<DetectorThread> detector_thread_;

  std::unique_ptr<ScanInput> scan_input_;
  ::ros::Subscriber detections_subscriber_;
  ::ros::Subscriber camera_info_subscriber_;
  ::ros::Subscriber color_subscriber_;  // the detector's input, or the keyframes' images
  ::ros::Subscriber depth_subscriber_;
  ::ros::Publisher map_publisher_;
  ::ros::Publisher objects_publisher_;
  ::ros::ServiceServer save_service_;

  // SLAM's best so far, one pose per scan; written on the main queue under trajectory_mutex_
  // (the detector's thread reads it), which is taken after mutex_ where both are held.
  mutable std::mutex trajectory_mutex_;
  std::vector<StampedPose> trajectory_;
  std::optional<double> last_map_stamp_;
  std::optional<::ros::WallTime> first_scan_wall_;
  std::size_t published_objects_ = 0;  // with mutex_ held
  // The earliest wall time of the next objects' snapshot (with mutex_ held).
  std::optional<::ros::WallTime> next_objects_wall_;
  bool shut_down_ = false;
  std::optional<std::pair<std::size_t, int>> saved_at_;  // scans and frames at the last save
  MappingTimings timings_;
};

}  // namespace semchain::ros1
