#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "core/rng.h"
#include "localization/amcl.h"
#include "localization/localization_map.h"
#include "localization/scan_match_relocalizer.h"
#include "mapping/map_io.h"
#include "semantic/keyframe_recognizer.h"
#include "semantic/observation_memory.h"
#include "semantic/prelocalization.h"
#include "semantic/semantic_map.h"
#include "sensors/camera.h"
#include "sensors/detection.h"
#include "sensors/laser_scan.h"

// The relocalization methods of DESIGN.md §4, run over what a robot records while it turns in
// place and moves off: its scans with odometry and its camera's detections.
//   amcl                AMCL initialised globally (laser only, nav2 defaults)
//   semantic-amcl       chain pre-localization (seed 000 §3.1) seeds AMCL with Gaussians around
//                       the hypotheses and weights its particles by the prior (seed 000 §3.2);
//                       laser-only AMCL until a frame shows two objects; every later such frame
//                       renews the prior (moved on by odometry in between), and re-seeds the
//                       particles when the filter reports a collapse
//   semantic-amcl-bow   semantic-amcl; when a frame's objects give no hypothesis, the bag of words
//                       finds the most similar keyframe, names the object hidden now and
//                       pre-localizes from its two chain neighbours (seed 000 §3.1 steps 3–4)
//   semantic-scanmatch  the hypotheses bound the window of branch-and-bound + Ceres (seed 001);
//                       after a full turn without two objects in view, windows around
//                       single-object hypotheses, then the whole map
//   scanmatch-global    the same matcher over the whole map (Cartographer-style baseline)
// The semantic methods pre-localize from every object seen during the last turn (see
// semantic::ObservationMemory). After a scan matcher has found the robot, AMCL tracks it.
namespace semchain::eval {

const std::vector<std::string>& RelocMethodNames();
bool IsRelocMethod(const std::string& name);
// semantic-scanmatch and scanmatch-global: a scan matcher finds the robot, AMCL then tracks.
bool IsScanMatcherMethod(const std::string& name);

// How the semantic methods use what the camera saw.
struct RelocMethodOptions {
  // Pre-localize from every object seen during the turn (carried by odometry into the current
  // frame), not only from the current frame's.
  bool observation_memory = true;
  semantic::ObservationMemoryOptions memory;
  // semantic-scanmatch: after a full turn without two objects forming a mapped pair, search
  // windows around single-object hypotheses (circles around the mapped objects of a seen class)
  // before the whole map.
  bool single_object = true;
  // semantic-scanmatch: while tracking, every frame's pre-localization checks the lock; a pose
  // that explains more of the objects seen than the tracked one is searched beside it, and the
  // scan matcher's better match is kept (a look-alike pair can lock the robot in the wrong place).
  bool recheck_lock = true;
};

// Everything a method may use about the environment, built once per map.
struct RelocMap {
  RelocMap(const mapping::MapImage& occupancy, const semantic::SemanticMap& semantic,
           const localization::AmclOptions& amcl,
           const semantic::PreLocalizationOptions& prelocalization,
           const localization::ScanMatchRelocalizerOptions& scan_match);

  mapping::MapImage occupancy;
  semantic::SemanticMap semantic;
  localization::AmclOptions amcl_options;
  localization::LocalizationMap localization;
  semantic::PreLocalizer prelocalizer;
  localization::ScanMatchRelocalizer matcher;
  RelocMethodOptions method;
  // The keyframes of the mapping run with their vocabulary (semantic-amcl-bow); may be null.
  std::shared_ptr<const semantic::KeyframeRecognizer> recognizer;
};

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
// after it).
RelocTrace RunRelocMethod(const std::string& method, const RelocMap& map,
                          const RelocRunInputs& inputs);

}  // namespace semchain::eval
