#include "ros/node_inputs.h"

#include <ros/console.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "detection/run_detection.h"
#include "ros/log_throttle.h"
#include "ros/ros_geometry.h"
#include "ros/ros_image.h"
#include "ros/ros_scan.h"

namespace semchain::ros1 {

std::optional<geometry_msgs::TransformStamped> LookUpTransform(const tf2_ros::Buffer& buffer,
                                                               const std::string& target,
                                                               const std::string& source,
                                                               const ::ros::Time& stamp,
                                                               double wait) {
  // Waits in wall time: tf2's own timeout runs on the ROS clock, which stands still once a
  // bag played with --clock has ended, so a scan whose odometry never comes would block the
  // node (and its services) for good.
  const ::ros::WallTime deadline = ::ros::WallTime::now() + ::ros::WallDuration(wait);
  std::string error;
  while (!buffer.canTransform(target, source, stamp, &error)) {
    if (::ros::WallTime::now() >= deadline || !::ros::ok()) {
      SEMCHAIN_WARN_THROTTLE(5.0, "semchain_ros: no transform %s -> %s at %.3f: %s", target.c_str(),
                             source.c_str(), stamp.toSec(), error.c_str());
      return std::nullopt;
    }
    error.clear();
    ::ros::WallDuration(0.001).sleep();
  }
  return buffer.lookupTransform(target, source, stamp);
}

std::optional<StampedScan> ScanWithOdometry(const tf2_ros::Buffer& buffer,
                                            const sensor_msgs::LaserScan& message,
                                            const NodeFrames& frames) {
  const std::optional<geometry_msgs::TransformStamped> odom_from_base = LookUpTransform(
      buffer, frames.odom_frame_id, frames.base_frame_id, message.header.stamp, 0.0);
  // The laser's mounting is static: the latest transform is its transform.
  const std::optional<geometry_msgs::TransformStamped> base_from_laser =
      LookUpTransform(buffer, frames.base_frame_id, message.header.frame_id, ::ros::Time(0), 0.0);
  if (!odom_from_base || !base_from_laser) return std::nullopt;
  StampedScan scan;
  scan.scan = FromLaserScanMsg(message).scan;
  scan.scan.timestamp = message.header.stamp.toSec();
  scan.odometry = PlanarPose(ToIsometry(odom_from_base->transform));
  scan.laser_pose = scan.odometry * PlanarPose(ToIsometry(base_from_laser->transform));
  return scan;
}

void CameraTracker::OnCameraInfo(const sensor_msgs::CameraInfo& message) {
  if (info_ && info_->header.frame_id == message.header.frame_id && info_->K == message.K &&
      info_->width == message.width) {
    return;
  }
  info_ = message;
  camera_.reset();
}

std::optional<MountedCamera> CameraTracker::Camera(const tf2_ros::Buffer& buffer,
                                                   const NodeFrames& frames) {
  if (camera_) return camera_;
  if (!info_) return std::nullopt;
  bool has_distortion = false;
  Result<PinholeCamera> intrinsics = FromCameraInfoMsg(*info_, &has_distortion);
  if (!intrinsics.ok()) {
    SEMCHAIN_WARN_THROTTLE(5.0, "semchain_ros: %s", intrinsics.status().message().c_str());
    return std::nullopt;
  }
  if (has_distortion) {
    ROS_WARN_ONCE(
        "semchain_ros: camera_info has distortion coefficients; they are not applied "
        "(give the node rectified images)");
  }
  // The camera's mounting is static: the latest transform is its transform.
  const std::optional<geometry_msgs::TransformStamped> base_from_camera = LookUpTransform(
      buffer, frames.base_frame_id, info_->header.frame_id, ::ros::Time(0), frames.tf_wait);
  if (!base_from_camera) return std::nullopt;
  MountedCamera camera;
  camera.intrinsics = *intrinsics;
  camera.robot_from_camera = ToIsometry(base_from_camera->transform);
  camera.max_range = max_range_;
  camera_ = camera;
  return camera_;
}

namespace {

// A depth image belongs to a colour image within half a frame of a 10 Hz camera.
constexpr double kPairingGapSeconds = 0.05;
// Images waiting for their partner: about a second of a 30 Hz camera.
constexpr std::size_t kWaitingImages = 30;

}  // namespace

sensor_msgs::ImageConstPtr RgbdDetector::TakePartner(
    std::deque<sensor_msgs::ImageConstPtr>* waiting, const ::ros::Time& stamp) {
  for (auto it = waiting->begin(); it != waiting->end(); ++it) {
    if (std::abs(((*it)->header.stamp - stamp).toSec()) > kPairingGapSeconds) continue;
    sensor_msgs::ImageConstPtr partner = *it;
    waiting->erase(waiting->begin(), std::next(it));  // older ones can no longer be paired
    return partner;
  }
  return nullptr;
}

void RgbdDetector::Wait(std::deque<sensor_msgs::ImageConstPtr>* waiting,
                        const sensor_msgs::ImageConstPtr& message, const char* what) {
  waiting->push_back(message);
  if (waiting->size() <= kWaitingImages) return;
  waiting->pop_front();
  SEMCHAIN_WARN_THROTTLE(5.0, "semchain_ros: a %s image found no partner with its stamp; dropped",
                         what);
}

std::optional<RgbdDetections> RgbdDetector::OnColorImage(
    const sensor_msgs::ImageConstPtr& message) {
  const sensor_msgs::ImageConstPtr depth = TakePartner(&depths_, message->header.stamp);
  if (!depth) {
    Wait(&colors_, message, "colour");
    return std::nullopt;
  }
  return Detect(*message, *depth);
}

std::optional<RgbdDetections> RgbdDetector::OnDepthImage(
    const sensor_msgs::ImageConstPtr& message) {
  const sensor_msgs::ImageConstPtr color = TakePartner(&colors_, message->header.stamp);
  if (!color) {
    Wait(&depths_, message, "depth");
    return std::nullopt;
  }
  return Detect(*color, *message);
}

std::optional<RgbdDetections> RgbdDetector::Detect(const sensor_msgs::Image& message,
                                                   const sensor_msgs::Image& depth_message) {
  Result<cv::Mat> rgb = ColorFromImageMsg(message);
  if (!rgb.ok()) {
    SEMCHAIN_WARN_THROTTLE(5.0, "semchain_ros: %s", rgb.status().message().c_str());
    return std::nullopt;
  }
  constexpr double kMillimetre = 0.001;
  Result<cv::Mat> depth = DepthFromImageMsg(depth_message, kMillimetre);
  if (!depth.ok() || depth->size() != rgb->size()) {
    SEMCHAIN_WARN_THROTTLE(
        5.0, "semchain_ros: depth image unusable (%s)",
        depth.ok() ? "not the colour image's size" : depth.status().message().c_str());
    return std::nullopt;
  }
  RgbdDetections frame;
  frame.frame = "camera/" + std::to_string(message.header.seq);
  frame.stamp = message.header.stamp.toSec();
  depth->convertTo(frame.depth_m, CV_32FC1, kMillimetre);
  const auto start = std::chrono::steady_clock::now();
  Result<std::vector<Detection>> detections = detector_->Detect(*rgb);
  frame.detect_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (!detections.ok()) {
    SEMCHAIN_WARN_THROTTLE(5.0, "semchain_ros: detector: %s",
                           detections.status().message().c_str());
    return std::nullopt;
  }
  const std::optional<MountedCamera> camera = camera_ ? camera_() : std::nullopt;
  detection::MeasureDepths(frame.depth_m, camera ? &*camera : nullptr,
                           detection::RunDetectionOptions(), *detections);
  frame.detections = std::move(*detections);
  frame.color = std::move(*rgb);
  return frame;
}

Result<std::unique_ptr<detection::YoloDetector>> LoadNodeDetector(const std::string& model,
                                                                  const std::string& class_map) {
  if (model.empty()) return std::unique_ptr<detection::YoloDetector>();
  return detection::LoadYoloDetector(model, "", detection::YoloOptions(), class_map);
}

std::string DescribeNodeDetector(const std::string& model, const std::string& class_map,
                                 const detection::YoloDetector& detector) {
  const cv::Size input = detector.options().input_size();
  return model + " (input " + std::to_string(input.width) + "x" + std::to_string(input.height) +
         ", " + std::to_string(detector.class_names().size()) + " classes" +
         (class_map.empty() ? std::string() : ", class map " + class_map) + ")";
}

nlohmann::json Spread(std::vector<double> values) {
  if (values.empty()) return nullptr;
  std::sort(values.begin(), values.end());
  double sum = 0.0;
  for (const double v : values) sum += v;
  const auto at = [&values](double q) {
    return values[static_cast<std::size_t>(q * static_cast<double>(values.size() - 1) + 0.5)];
  };
  return {{"mean", sum / static_cast<double>(values.size())},
          {"median", at(0.5)},
          {"p95", at(0.95)},
          {"max", values.back()}};
}

}  // namespace semchain::ros1
