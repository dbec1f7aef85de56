#pragma once

#include <optional>
#include <vector>

#include "core/pose2.h"
#include "localization/localizer.h"
#include "sensors/laser_scan.h"

// What a Localizer did over a recorded run, scan by scan: the poses it gave, the work it did,
// the pre-localization it used and, on request, its particles (what `semchain localize` prints
// and draws and what the relocalization benchmark scores).
namespace semchain::localization {

// The particles of the method's AMCL after one filter update (for pictures of the filter
// converging).
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
  // With particle snapshots asked for (RelocTraceRecorder), in time order: the first filter
  // update, the one at prelocalization_scan or the first after it, every n-th, and the last.
  // Scan matchers have no particles before they found the robot (AMCL tracks from there).
  std::vector<ParticleSnapshot> particle_snapshots;
};

// Feeds a Localizer its scans one by one and keeps its RelocTrace.
//
//   Localizer localizer(map, method, options);
//   localizer.AddFrame(frame);  // every camera frame of the run
//   RelocTraceRecorder recorder(0);
//   for (const StampedScan& scan : scans) recorder.AddScan(scan, localizer);
//   const RelocTrace trace = recorder.Finish(localizer);
class RelocTraceRecorder {
 public:
  static constexpr int kDefaultParticlesKept = 2000;

  // 'particles_every' 0: no particle snapshots (nothing is copied); n > 0: snapshots of every
  // n-th filter update (and the ones RelocTrace::particle_snapshots names), outside the measured
  // CPU time, each keeping at most 'particles_kept' particles.
  explicit RelocTraceRecorder(int particles_every, int particles_kept = kDefaultParticlesKept);

  // Gives 'scan' to 'localizer', timed on this thread's CPU clock, and notes what followed.
  void AddScan(const StampedScan& scan, Localizer& localizer);

  // The trace of the scans given, with the localizer's counts at the end; once, after the last.
  RelocTrace Finish(const Localizer& localizer);

 private:
  void RecordParticles(const Amcl& filter, const StampedScan& scan);

  int particles_every_;
  int particles_kept_;
  RelocTrace trace_;
  double cpu_seconds_ = 0.0;
  int recorded_updates_ = 0;  // the filter's update count when last looked at
  bool snapped_prelocalized_ = false;
  // The last update's particles when they were not kept, in case it turns out to be the last.
  std::optional<ParticleSnapshot> unrecorded_;
};

}  // namespace semchain::localization
