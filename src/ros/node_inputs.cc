#include "ros/node_inputs.h"

#include <ros/console.h>

#include <algorithm>
#include <cmath>

#include "detection/run_detection.h"
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
      ROS_WARN_THROTTLE(5.0, "semchain_ros: no transform %s -> %s at %.3f: %s", target.c_str(),
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
      buffer, frames.odom_frame_id, frames.base_frame_id, message.header.stamp, frames.tf_wait);
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
  if (!info_) {
    ROS_WARN_THROTTLE(5.0, "semchain_ros: detections before any camera_info; skipped");
    return std::nullopt;
  }
  bool has_distortion = false;
  Result<PinholeCamera> intrinsics = FromCameraInfoMsg(*info_, &has_distortion);
  if (!intrinsics.ok()) {
    ROS_WARN_THROTTLE(5.0, "semchain_ros: %s", intrinsics.status().message().c_str());
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

std::optional<RgbdDetections> RgbdDetector::OnColorImage(const sensor_msgs::Image& message) {
  Result<cv::Mat> rgb = ColorFromImageMsg(message);
  if (!rgb.ok()) {
    ROS_WARN_THROTTLE(5.0, "semchain_ros: %s", rgb.status().message().c_str());
    return std::nullopt;
  }
  // The aligned depth of the same moment: taken within half a frame of the colour image.
  if (!latest_depth_ ||
      std::abs((latest_depth_->header.stamp - message.header.stamp).toSec()) > 0.05) {
    ROS_WARN_THROTTLE(5.0, "semchain_ros: no depth image with the colour image's stamp");
    return std::nullopt;
  }
  constexpr double kMillimetre = 0.001;
  Result<cv::Mat> depth = DepthFromImageMsg(*latest_depth_, kMillimetre);
  if (!depth.ok() || depth->size() != rgb->size()) {
    ROS_WARN_THROTTLE(
        5.0, "semchain_ros: depth image unusable (%s)",
        depth.ok() ? "not the colour image's size" : depth.status().message().c_str());
    return std::nullopt;
  }
  RgbdDetections frame;
  frame.stamp = message.header.stamp.toSec();
  depth->convertTo(frame.depth_m, CV_32FC1, kMillimetre);
  Result<std::vector<Detection>> detections = detector_->Detect(*rgb);
  if (!detections.ok()) {
    ROS_WARN_THROTTLE(5.0, "semchain_ros: detector: %s", detections.status().message().c_str());
    return std::nullopt;
  }
  detection::MeasureDepths(frame.depth_m, detection::RunDetectionOptions(), *detections);
  frame.detections = std::move(*detections);
  frame.color = std::move(*rgb);
  return frame;
}

Result<std::unique_ptr<detection::YoloDetector>> LoadNodeDetector(const std::string& model) {
  if (model.empty()) return std::unique_ptr<detection::YoloDetector>();
  return detection::LoadYoloDetector(model, "", detection::YoloOptions());
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
