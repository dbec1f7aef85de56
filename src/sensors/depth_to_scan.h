#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "sensors/camera.h"
#include "sensors/laser_scan.h"

// A depth image turned into a virtual planar laser scan (seed 004 §1.3, eq. 6–8, the idea of
// ROS depthimage_to_laserscan). The paper works in the optical frame (θ = atan(x/z),
// r = sqrt(x² + z²)), which is right only for a level camera; we transform every pixel into the
// robot frame with the camera's mounting first, so a pitched camera gives true horizontal
// angles, ranges and heights above the floor.
namespace semchain {

struct DepthToScanOptions {
  // The height band (metres above the floor) whose points count as obstacles. Points lower
  // than the floor band are the floor itself (plus depth noise); points higher than the robot
  // cannot hit it. Defaults: 5 cm above the floor (seed 004 §3.3 of DESIGN.md) up to 0.6 m, the
  // height of a small indoor base such as a TurtleBot 2 with a camera on top.
  double min_height_meters = 0.05;
  double max_height_meters = 0.6;
  // Number of bins N of eq. 7. 0 picks the largest N for which every image row puts a pixel
  // into every bin it spans (bins as wide as the widest angle between two adjacent columns),
  // so a thin obstacle seen by a few rows leaves no empty bins between its pixels; N = image
  // width would, because equal-angle bins are narrower than the central columns.
  int beams = 0;
  // Depths outside (min, max] are ignored; 0 for max takes the camera's max_range.
  double min_depth_meters = 0.1;
  double max_depth_meters = 0.0;

  bool Validate(std::string* error) const;
};

// Converts depth images of one mounted camera; the per-pixel geometry is computed once.
class DepthToScanConverter {
 public:
  DepthToScanConverter(const MountedCamera& camera, const DepthToScanOptions& options);

  // The virtual scan of 'depth_meters' (CV_32FC1 of the camera's size, 0 = no measurement):
  // per bin the nearest horizontal distance of a point inside the height band, measured from
  // the scan origin (see robot_from_scan()); bins without such a point read max_range
  // ("no return"). Beam i points at angle_min + i * angle_increment in the scan frame.
  LaserScan Convert(const cv::Mat& depth_meters, double timestamp) const;

  // The scan frame on the robot: the camera's position projected onto the floor, with the
  // robot's heading, so that a scan angle is an angle around the camera's vertical axis.
  const Pose2& robot_from_scan() const { return robot_from_scan_; }

 private:
  struct PixelRay {
    float horizontal_per_depth;  // horizontal distance per metre of depth
    float height_per_depth;      // height change per metre of depth
    int bin;                     // eq. 7, -1 when the ray has no horizontal direction
  };

  MountedCamera camera_;
  DepthToScanOptions options_;
  Pose2 robot_from_scan_;
  double camera_height_ = 0.0;
  double angle_min_ = 0.0;
  double angle_increment_ = 0.0;
  int beams_ = 0;
  double max_range_ = 0.0;
  std::vector<PixelRay> rays_;  // row-major, one per pixel
};

}  // namespace semchain
