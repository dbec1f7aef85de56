#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "ros/bag_layout.h"
#include "ros/run_info.h"

// The options of `semchain bag import`, and what its steps share while they run.
namespace semchain::ros1 {

struct BagImportOptions {
  BagTopics topics;
  // 'odom' and 'base' are looked up in tf; the laser's and camera's frames are those of their
  // messages' headers ('laser' and 'camera' stand in for a message that names none).
  BagFrames frames;
  // The largest gap between a colour image and its depth image, and between a frame and its
  // detections record, that still pairs them (seconds).
  double max_pair_gap_s = 0.02;
  // camera.yaml's max_range (metres) for a bag without run info; by default the deepest depth
  // reading of the frames, rounded up to 0.1 m (6 m without frames).
  std::optional<double> camera_max_range;
  // A camera.yaml (io/camera_io.h) giving the camera's intrinsics, mounting and max_range,
  // in place of camera_info and tf: for a bag whose camera_info is uncalibrated, or whose tf
  // lacks the camera. Empty: from the bag.
  std::filesystem::path camera_yaml;
  // false: the scans, odometry and truth alone (no frames, no camera.yaml), for a bag whose
  // camera is not wanted or not calibrated.
  bool import_camera = true;
  bool show_progress = true;  // a progress bar on stderr when it is a terminal
};

// What the import steps share.
struct ImportContext {
  BagImportOptions options;
  std::optional<RunInfo> run_info;  // the bag's /semchain/run_info, if any
  std::int64_t stamp_offset_seconds = 0;
  std::vector<std::string> warnings;  // one line each, for the user

  std::int64_t max_pair_gap_ns() const {
    return static_cast<std::int64_t>(options.max_pair_gap_s * 1e9 + 0.5);
  }
};

}  // namespace semchain::ros1
