#include "sensors/depth_to_scan.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/angles.h"
#include "core/check.h"

namespace semchain {

bool DepthToScanOptions::Validate(std::string* error) const {
  if (!(min_height_meters < max_height_meters)) {
    *error = "min_height_meters must be below max_height_meters";
    return false;
  }
  if (beams < 0) {
    *error = "beams must be >= 0";
    return false;
  }
  if (!(min_depth_meters >= 0.0) || !(max_depth_meters >= 0.0) ||
      (max_depth_meters > 0.0 && max_depth_meters <= min_depth_meters)) {
    *error = "depth limits must satisfy 0 <= min_depth_meters < max_depth_meters (or max 0)";
    return false;
  }
  return true;
}

namespace {

// The largest bin count whose bins are at least as wide as the angle between any two adjacent
// pixels of a row ('angles' row-major, 'width' per row).
int DefaultBeams(const std::vector<double>& angles, int width, double field_of_view) {
  double widest_step = 0.0;
  for (std::size_t i = 0; i + 1 < angles.size(); ++i) {
    if ((i + 1) % static_cast<std::size_t>(width) == 0) continue;  // next pixel is a new row
    widest_step = std::max(widest_step, std::abs(NormalizeAngle(angles[i + 1] - angles[i])));
  }
  if (widest_step <= 0.0) return width;
  return std::max(1, static_cast<int>(std::floor(field_of_view / widest_step)));
}

}  // namespace

DepthToScanConverter::DepthToScanConverter(const MountedCamera& camera,
                                           const DepthToScanOptions& options)
    : camera_(camera), options_(options) {
  std::string error;
  SEMCHAIN_CHECK(options.Validate(&error));
  const Eigen::Isometry3d& robot_from_camera = camera.robot_from_camera;
  const Eigen::Matrix3d rotation = robot_from_camera.rotation();
  const Eigen::Vector3d position = robot_from_camera.translation();
  robot_from_scan_ = Pose2(position.x(), position.y(), 0.0);
  camera_height_ = position.z();
  max_range_ = options.max_depth_meters > 0.0 ? options.max_depth_meters : camera.max_range;
  const int width = camera.intrinsics.width;
  const int height = camera.intrinsics.height;

  // Angles are taken relative to the optical axis's horizontal direction, so a field of view
  // that straddles ±π (a camera looking backwards) still gives one contiguous interval [α, β].
  const Eigen::Vector3d axis = rotation.col(2);
  const double axis_yaw = std::atan2(axis.y(), axis.x());
  std::vector<double> relative_angle(static_cast<std::size_t>(width * height), 0.0);
  rays_.resize(relative_angle.size());
  double alpha = std::numeric_limits<double>::infinity();
  double beta = -alpha;
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      const std::size_t i = static_cast<std::size_t>(v * width + u);
      // The robot-frame displacement per metre of depth of pixel (u, v) (eq. 2 applied to the
      // back-projected point at z = 1).
      const Eigen::Vector3d d = rotation * camera.intrinsics.Backproject(u, v, 1.0);
      const double horizontal = std::hypot(d.x(), d.y());
      rays_[i] = {static_cast<float>(horizontal), static_cast<float>(d.z()), -1};
      if (horizontal < 1e-9) continue;  // looking straight down or up: no bearing
      relative_angle[i] = NormalizeAngle(std::atan2(d.y(), d.x()) - axis_yaw);
      alpha = std::min(alpha, relative_angle[i]);
      beta = std::max(beta, relative_angle[i]);
    }
  }
  SEMCHAIN_CHECK(alpha < beta);
  beams_ = options.beams > 0 ? options.beams : DefaultBeams(relative_angle, width, beta - alpha);
  // Eq. 7: n = N (θ − α) / (β − α), with θ = β put into the last bin.
  const double scale = beams_ / (beta - alpha);
  for (std::size_t i = 0; i < rays_.size(); ++i) {
    if (rays_[i].horizontal_per_depth < 1e-9f) continue;
    const int bin = static_cast<int>(std::floor((relative_angle[i] - alpha) * scale));
    rays_[i].bin = std::clamp(bin, 0, beams_ - 1);
  }
  angle_increment_ = (beta - alpha) / beams_;
  angle_min_ = axis_yaw + alpha + 0.5 * angle_increment_;  // the centre of bin 0
}

LaserScan DepthToScanConverter::Convert(const cv::Mat& depth_meters, double timestamp) const {
  SEMCHAIN_CHECK(depth_meters.type() == CV_32FC1);
  SEMCHAIN_CHECK(depth_meters.cols == camera_.intrinsics.width &&
                 depth_meters.rows == camera_.intrinsics.height);
  LaserScan scan;
  scan.timestamp = timestamp;
  scan.angle_min = angle_min_;
  scan.angle_increment = angle_increment_;
  scan.max_range = max_range_;
  scan.ranges.assign(static_cast<std::size_t>(beams_), max_range_);
  const double min_depth = options_.min_depth_meters;
  for (int v = 0; v < depth_meters.rows; ++v) {
    const float* row = depth_meters.ptr<float>(v);
    for (int u = 0; u < depth_meters.cols; ++u) {
      const double z = row[u];
      if (!(z > min_depth) || z > max_range_) continue;  // also skips NaN and 0 (no reading)
      const PixelRay& ray = rays_[static_cast<std::size_t>(v * depth_meters.cols + u)];
      if (ray.bin < 0) continue;
      // The height band of DESIGN.md §3.3: floor points and points above the robot are no
      // obstacles.
      const double height = camera_height_ + z * ray.height_per_depth;
      if (height < options_.min_height_meters || height > options_.max_height_meters) continue;
      // Eq. 8, measured horizontally in the robot frame; the nearest point per bin wins.
      double& range = scan.ranges[static_cast<std::size_t>(ray.bin)];
      range = std::min(range, z * ray.horizontal_per_depth);
    }
  }
  return scan;
}

}  // namespace semchain
