#pragma once

#include <geometry_msgs/TransformStamped.h>
#include <ros/time.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_ros/buffer.h>

#include <deque>
#include <functional>
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
  // ~tf_wait: s (wall time) the camera's mounting is waited for in tf. Scans wait for their
  // odometry in ScanInput's filter instead, as long as its queue allows.
  double tf_wait = 0.5;
};

// target_from_source at 'stamp' (waiting up to 'wait' seconds); unknown: a throttled warning.
std::optional<geometry_msgs::TransformStamped> LookUpTransform(const tf2_ros::Buffer& buffer,
                                                               const std::string& target,
                                                               const std::string& source,
                                                               const ::ros::Time& stamp,
                                                               double wait);

// 'message' with the odometry (tf odom → base_link at its stamp) and the laser's mounting
// (base → the scan's frame, static), looked up without waiting (ScanInput releases a scan once
// tf knows them); nullopt with a throttled warning when tf does not know them.
std::optional<StampedScan> ScanWithOdometry(const tf2_ros::Buffer& buffer,
                                            const sensor_msgs::LaserScan& message,
                                            const NodeFrames& frames);

// The camera from /camera/color/camera_info and tf, once both are known.
class CameraTracker {
 public:
  explicit CameraTracker(double max_range) : max_range_(max_range) {}
  void OnCameraInfo(const sensor_msgs::CameraInfo& message);
  bool has_info() const { return info_.has_value(); }
  // The camera (intrinsics and its mounting on 'base_frame'); nullopt while camera_info is
  // missing (has_info() says so; the caller decides what becomes of its frame), or with a
  // throttled warning while the transform is.
  std::optional<MountedCamera> Camera(const tf2_ros::Buffer& buffer, const NodeFrames& frames);

 private:
  double max_range_;
  std::optional<sensor_msgs::CameraInfo> info_;
  std::optional<MountedCamera> camera_;
};

// A colour image's detections by ~detector, with the aligned depth image of the same moment.
struct RgbdDetections {
  std::string frame;  // "camera/<colour image's header.seq>"
  double stamp = 0.0;
  std::vector<Detection> detections;
  cv::Mat color;           // RGB
  cv::Mat depth_m;         // CV_32FC1, metres (0: no reading)
  double detect_ms = 0.0;  // wall time of the detector on this frame (OpenCV runs it threaded)
};

// Pairs /camera/color/image_raw with /camera/depth/image_raw by stamp and runs the detector on
// each pair. The two topics come on separate connections, so either image of a moment may
// arrive first: each waits (a few at most) for its partner, and the call that completes a pair
// returns its detections.
class RgbdDetector {
 public:
  // The camera when it is known (camera_info and tf), asked once per completed pair: it tells
  // the depth image's floor pixels from the objects'. Without one no pixel is floor.
  using CameraSource = std::function<std::optional<MountedCamera>()>;

  explicit RgbdDetector(detection::YoloDetector* detector, CameraSource camera = {})
      : detector_(detector), camera_(std::move(camera)) {}
  // The detections of the frame this image completes; nullopt while its partner has not come,
  // or with a throttled warning when the pair cannot be used.
  std::optional<RgbdDetections> OnColorImage(const sensor_msgs::ImageConstPtr& message);
  std::optional<RgbdDetections> OnDepthImage(const sensor_msgs::ImageConstPtr& message);

 private:
  std::optional<RgbdDetections> Detect(const sensor_msgs::Image& color,
                                       const sensor_msgs::Image& depth);
  // Takes the image of 'waiting' with 'stamp''s moment (and drops the older ones, which can no
  // longer be paired); null when none.
  static sensor_msgs::ImageConstPtr TakePartner(std::deque<sensor_msgs::ImageConstPtr>* waiting,
                                                const ::ros::Time& stamp);
  static void Wait(std::deque<sensor_msgs::ImageConstPtr>* waiting,
                   const sensor_msgs::ImageConstPtr& message, const char* what);

  detection::YoloDetector* detector_;
  CameraSource camera_;
  std::deque<sensor_msgs::ImageConstPtr> colors_;  // waiting for their depth image
  std::deque<sensor_msgs::ImageConstPtr> depths_;  // waiting for their colour image
};

// ~detector's model (no detector, null, when 'model' is empty) with ~class_map's map when
// 'class_map' is not empty; the error names the file.
Result<std::unique_ptr<detection::YoloDetector>> LoadNodeDetector(const std::string& model,
                                                                  const std::string& class_map);
// "M.onnx (input 320x256, 10 classes, class map C.yaml)", for the start-up line ('class_map'
// empty: none).
std::string DescribeNodeDetector(const std::string& model, const std::string& class_map,
                                 const detection::YoloDetector& detector);

// Mean, median, 95th percentile and maximum of 'values' as JSON (null when empty).
nlohmann::json Spread(std::vector<double> values);

}  // namespace semchain::ros1
