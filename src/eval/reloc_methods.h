#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "localization/localizer.h"
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

// The particles of the method's AMCL after one filter update (for pictures of the filter
// converging; see RelocRunInputs::record_particles_every).
struct ParticleSnapshot {
  int scan = 0;                 // index of the scan whose update it follows
  double time = 0.0;            // that scan's timestamp, seconds
  int particles = 0;            // the filter's particle count then (KLD-adaptive)
  std::vector<Pose2> poses;     // an evenly strided subsample of the particles ...
  std::vector<double> weights;  // ... and their normalised weights
};

// The pose a method gives after each scan (nothing while it has no estimate), the work it did
// and the pre-localization it used.
struct RelocTrace {
  std::vector<std::optional<Pose2>> estimates;  // one per scan
  std::vector<double> cpu_seconds;              // cumulative, one per scan
  // Scan-matcher methods: the part of cpu_seconds spent searching for the robot (observing,
  // pre-localization, branch and bound, Ceres) before tracking began, cumulative, one per scan;
  // the rest is AMCL (seeding the tracking filter with the match, then tracking).
  std::vector<double> search_cpu_seconds;
  std::vector<int> iterations;             // cumulative filter updates / matcher runs
  std::optional<Pose2> prelocalization;    // the first best hypothesis, when there was one
  int prelocalization_scan = -1;           // the scan it was made at
  int prelocalizations = 0;                // times pre-localization was run with ≥ 2 objects
  int single_object_prelocalizations = 0;  // ... with single-object hypotheses
  int hidden_object_prelocalizations = 0;  // ... from a hidden object's neighbours (BoW)
  int undecided_prelocalizations = 0;      // ... leaving look-alike places (nothing locked)
  int lock_corrections = 0;                // moves to a place explaining more objects
  int lock_rechecks = 0;                   // lock re-checks searched (semantic-scanmatch)
  // With RelocRunInputs::record_particles_every > 0, in time order: the first filter update,
  // the one at prelocalization_scan or the first after it, every n-th, and the last. Scan
  // matchers have no particles before they found the robot (AMCL tracks from there).
  std::vector<ParticleSnapshot> particle_snapshots;
};

struct RelocRunInputs {
  std::vector<StampedScan> scans;
  std::vector<RelocFrame> frames;  // in time order
  MountedCamera camera;
  std::uint64_t seed = 1;
  // 0: no particle snapshots (nothing is copied); n > 0: snapshots of every n-th filter update
  // (and the ones RelocTrace::particle_snapshots names), outside the measured CPU time.
  int record_particles_every = 0;
  int record_particles_max = 2000;  // particles kept per snapshot, at most
};

// Runs 'method' over the scans (frames are used at the scan with the same stamp or the first
// after it), its filter seeded with inputs.seed (options.seed is not used).
RelocTrace RunRelocMethod(localization::LocalizationMethod method,
                          const localization::LocalizerMap& map,
                          const localization::LocalizerOptions& options,
                          const RelocRunInputs& inputs);

}  // namespace semchain::eval
