#pragma once

#include <filesystem>
#include <opencv2/core.hpp>
#include <string>

#include "core/status.h"

// The RGB-D frames of a run: RUN/<frame>.png (8-bit colour) and RUN/<frame>_depth.png (16-bit
// depth in units of camera.yaml's depth_scale, 0 = no measurement), where <frame> is the name
// used in detections.jsonl, e.g. "frames/000123".
namespace semchain {

// Paths of the colour and depth images of 'frame' in 'run_dir'.
std::filesystem::path ColorImagePath(const std::filesystem::path& run_dir,
                                     const std::string& frame);
std::filesystem::path DepthImagePath(const std::filesystem::path& run_dir,
                                     const std::string& frame);

// The colour image in RGB order (CV_8UC3). A missing or undecodable file is an error naming it.
Result<cv::Mat> ReadColorImage(const std::filesystem::path& path);

// The depth image in metres (CV_32FC1, 0 where there is no measurement). The file must be a
// single-channel 16-bit PNG; 'expected_size' (when not empty) must match its size.
Result<cv::Mat> ReadDepthImage(const std::filesystem::path& path, double depth_scale,
                               cv::Size expected_size = {});

}  // namespace semchain
