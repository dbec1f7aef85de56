#pragma once

#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include <opencv2/core.hpp>
#include <string>

#include "core/status.h"
#include "sensors/camera.h"

// Images and camera calibration between a run (colour PNGs in RGB, 16-bit depth PNGs in units
// of camera.yaml's depth_scale) and sensor_msgs. Depth follows REP 118: 16UC1 in millimetres,
// 32FC1 in metres; a run whose depth unit is not the millimetre goes out as 32FC1.
namespace semchain::ros1 {

// An rgb8 image of 'rgb' (CV_8UC3, RGB order).
sensor_msgs::Image ToColorImageMsg(const cv::Mat& rgb, const std_msgs::Header& header);

// The depth image of 'raw' (CV_16UC1, units of 'depth_scale' metres, 0 = no measurement):
// 16UC1 as it is when the unit is the millimetre, else 32FC1 metres (0 stays 0).
sensor_msgs::Image ToDepthImageMsg(const cv::Mat& raw, double depth_scale,
                                   const std_msgs::Header& header);

// The colour image of 'msg' in RGB order (CV_8UC3): rgb8, bgr8, rgba8, bgra8 or mono8; another
// encoding, or data that does not fill the declared size, is an error.
Result<cv::Mat> ColorFromImageMsg(const sensor_msgs::Image& msg);

// The depth image of 'msg' as CV_16UC1 in units of 'depth_scale' metres: 16UC1 (and mono16)
// is taken as millimetres, 32FC1 as metres; a reading that is not finite, not positive or past
// what 16 bits hold becomes 0 (no measurement).
Result<cv::Mat> DepthFromImageMsg(const sensor_msgs::Image& msg, double depth_scale);

// 'metres' (CV_32FC1 or CV_64FC1) as CV_16UC1 in units of 'depth_scale' metres, rounded; a
// reading that is not finite, not positive or past what 16 bits hold becomes 0 (no measurement).
cv::Mat MetresToDepthUnits(const cv::Mat& metres, double depth_scale);

// A camera_info of 'camera' (no distortion; P = K | 0).
sensor_msgs::CameraInfo ToCameraInfoMsg(const PinholeCamera& camera,
                                        const std_msgs::Header& header);

// The pinhole intrinsics of 'msg' (K, width, height); a zero focal length or size is an error.
// Distortion is not modelled: 'has_distortion' tells whether D holds a non-zero coefficient.
Result<PinholeCamera> FromCameraInfoMsg(const sensor_msgs::CameraInfo& msg, bool* has_distortion);

}  // namespace semchain::ros1
