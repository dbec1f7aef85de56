#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "core/status.h"

// The bag's /semchain/run_info message (std_msgs/String, latched, one per bag): what a run holds
// that no ROS message carries, so that `bag import` gives back the run `bag export` was given.
// A JSON object:
//   {"format": "semchain-run-info", "version": 1,
//    "stamp_offset_s": 1,                       whole seconds added to every stamp (bag_time.h)
//    "camera": {"max_range": 6, "depth_scale": 0.001, "frame_rate_hz": 2},   camera.yaml's
//    "world_yaml": "..."}                       RUN/world.yaml, when the run has one
// Bags recorded on a robot have none: their stamps are used as they are.
namespace semchain::ros1 {

struct CameraExtras {
  double max_range = 0.0;
  double depth_scale = 0.001;
  double frame_rate_hz = 0.0;
};

struct RunInfo {
  std::int64_t stamp_offset_seconds = 0;
  std::optional<CameraExtras> camera;
  std::optional<std::string> world_yaml;
};

std::string FormatRunInfo(const RunInfo& info);

// Parses a run_info message; 'where' prefixes errors.
Result<RunInfo> ParseRunInfo(const std::string& text, const std::string& where);

}  // namespace semchain::ros1
