#include "semantic/detection_points.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/transforms.h"

namespace semchain::semantic {

std::vector<Eigen::Vector3d> DetectionWorldPoints(const Detection& detection,
                                                  const cv::Mat& depth_m,
                                                  const MountedCamera& camera,
                                                  const Pose2& robot_pose, double class_extent,
                                                  const DetectionPointOptions& options) {
  std::vector<Eigen::Vector3d> points;
  if (detection.score < options.min_score || !(detection.depth_m > 0.0)) return points;
  const double box_width = detection.box[2] - detection.box[0];
  const double box_height = detection.box[3] - detection.box[1];
  const double trim_x = std::max(options.min_trim_px, options.box_trim_fraction * box_width);
  const double trim_y = std::max(options.min_trim_px, options.box_trim_fraction * box_height);
  // Box edges are pixel boundaries; pixel u covers [u - 0.5, u + 0.5).
  const int u0 = std::max(0, static_cast<int>(std::ceil(detection.box[0] + trim_x - 0.5)));
  const int u1 =
      std::min(depth_m.cols - 1, static_cast<int>(std::floor(detection.box[2] - trim_x - 0.5)));
  const int v0 = std::max(0, static_cast<int>(std::ceil(detection.box[1] + trim_y - 0.5)));
  const int v1 =
      std::min(depth_m.rows - 1, static_cast<int>(std::floor(detection.box[3] - trim_y - 0.5)));
  const double gate = std::clamp(options.depth_gate_factor * class_extent, options.min_depth_gate,
                                 options.max_depth_gate);
  for (int v = v0; v <= v1; v += options.pixel_stride) {
    const float* row = depth_m.ptr<float>(v);
    for (int u = u0; u <= u1; u += options.pixel_stride) {
      const double z = row[u];
      if (!(z > 0.0) || std::abs(z - detection.depth_m) > gate) continue;
      const Eigen::Vector3d camera_point = camera.intrinsics.Backproject(u, v, z);
      const Eigen::Vector3d robot_point = CameraToRobot(camera.robot_from_camera, camera_point);
      const Eigen::Vector3d world_point = RobotToWorld(robot_pose, robot_point);
      if (world_point.z() < options.min_height) continue;
      points.push_back(world_point);
    }
  }
  return points;
}

std::vector<FreeRay> FreeSpaceRays(const cv::Mat& depth_m, const MountedCamera& camera,
                                   const Pose2& robot_pose, const FreeSpaceOptions& options) {
  std::vector<FreeRay> rays;
  const Eigen::Vector3d camera_robot = camera.robot_from_camera.translation();
  const Eigen::Vector2d origin = RobotToWorld(robot_pose, camera_robot).head<2>();
  for (int u = 0; u < depth_m.cols; u += options.column_stride) {
    double nearest = std::numeric_limits<double>::infinity();
    Eigen::Vector2d nearest_point = origin;
    for (int v = 0; v < depth_m.rows; ++v) {
      const double z = depth_m.at<float>(v, u);
      if (!(z > 0.0)) continue;
      const Eigen::Vector3d robot_point =
          CameraToRobot(camera.robot_from_camera, camera.intrinsics.Backproject(u, v, z));
      if (robot_point.z() < options.min_height || robot_point.z() > options.max_height) continue;
      const double range = (robot_point.head<2>() - camera_robot.head<2>()).norm();
      if (range < nearest) {
        nearest = range;
        nearest_point = robot_point.head<2>();
      }
    }
    if (!std::isfinite(nearest)) continue;
    const Eigen::Vector2d direction = (nearest_point - camera_robot.head<2>()) / nearest;
    const Eigen::Vector2d end =
        camera_robot.head<2>() + direction * std::max(0.0, nearest - options.surface_margin);
    rays.push_back({u, origin, PosePoint(end, robot_pose), PosePoint(nearest_point, robot_pose)});
  }
  return rays;
}

Eigen::Vector2d PosePoint(const Eigen::Vector2d& point, const Pose2& robot_pose) {
  // The z of the point does not enter x and y: a rotation about z.
  return RobotToWorld(robot_pose, Eigen::Vector3d(point.x(), point.y(), 0.0)).head<2>();
}

FreeRay PoseRay(const FreeRay& ray, const Pose2& robot_pose) {
  return {ray.column, PosePoint(ray.from, robot_pose), PosePoint(ray.to, robot_pose),
          PosePoint(ray.surface, robot_pose)};
}

}  // namespace semchain::semantic
