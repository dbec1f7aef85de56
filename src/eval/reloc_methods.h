#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "localization/localizer.h"
#include "localization/reloc_trace.h"
#include "sensors/camera.h"
#include "sensors/detection.h"
#include "sensors/laser_scan.h"

// The relocalization methods of DESIGN.md §4 (localization::Localizer) run over what a robot
// records while it turns in place and moves off: its scans with odometry and its camera's
// detections; the trace is what the benchmark scores.
namespace semchain::eval {

// One camera frame of a run, taken at the time of a scan.
struct RelocFrame {
  double stamp = 0.0;
  std::vector<Detection> detections;
  std::filesystem::path image;  // the colour image (semantic-amcl-bow)
};

struct RelocRunInputs {
  std::vector<StampedScan> scans;
  std::vector<RelocFrame> frames;  // in time order
  MountedCamera camera;
  std::uint64_t seed = 1;
  // 0: no particle snapshots (nothing is copied); n > 0: snapshots of every n-th filter update
  // (and the ones localization::RelocTrace::particle_snapshots names), outside the measured CPU
  // time.
  int record_particles_every = 0;
  // Particles kept per snapshot, at most.
  int record_particles_max = localization::RelocTraceRecorder::kDefaultParticlesKept;
};

// Runs 'method' over the scans (frames are used at the scan with the same stamp or the first
// after it), its filter seeded with inputs.seed (options.seed is not used).
localization::RelocTrace RunRelocMethod(localization::LocalizationMethod method,
                                        const localization::LocalizerMap& map,
                                        const localization::LocalizerOptions& options,
                                        const RelocRunInputs& inputs);

}  // namespace semchain::eval
