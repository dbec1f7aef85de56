#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/rng.h"
#include "core/status.h"
#include "sensors/camera.h"
#include "sensors/detection.h"
#include "sim/route_follower.h"
#include "sim/scene.h"

// The camera side of a simulation run: renders RGB-D frames at the camera rate, writes them
// under RUN/frames/ and collects the simulated detector's output for RUN/detections.jsonl.
namespace semchain::sim {

class FrameRecorder {
 public:
  // Frames of the robot camera of 'scene.world()', noise seeded from 'seed', into 'run_dir'.
  FrameRecorder(const Scene& scene, std::uint64_t seed, const std::filesystem::path& run_dir);

  // Creates RUN/frames.
  Status Open();
  // Takes a frame when one is due at 'sample.time': frames are taken at the first scan instant
  // at or after each multiple of the camera period, so each frame shares a scan's timestamp.
  Status MaybeCapture(const TrajectorySample& sample);
  // Writes RUN/detections.jsonl.
  Status Close();

  int count() const { return static_cast<int>(detections_.size()); }

 private:
  const Scene& scene_;
  MountedCamera camera_;
  std::filesystem::path run_dir_;
  double period_s_;
  double next_time_s_ = 0.0;
  Rng detection_rng_;
  Rng depth_noise_rng_;
  std::vector<FrameDetections> detections_;
};

}  // namespace semchain::sim
