#pragma once

#include <cstdint>

#include "localization/observation_memory.h"
#include "localization/scan_tracking.h"

namespace semchain::localization {

// How the semantic methods use what the camera saw.
struct LocalizerOptions {
  // Pre-localize from every object seen during the turn (carried by odometry into the current
  // frame), not only from the current frame's.
  bool observation_memory = true;
  ObservationMemoryOptions memory;
  // semantic-scanmatch: after a full turn without two objects forming a mapped pair, search
  // windows around single-object hypotheses (circles around the mapped objects of a seen class)
  // before the whole map.
  bool single_object = true;
  // semantic-scanmatch: while tracking, every frame's pre-localization checks the lock; a pose
  // that explains more of the objects seen than the tracked one is searched beside it, and the
  // scan matcher's better match is kept (a look-alike pair can lock the robot in the wrong place).
  bool recheck_lock = true;
  // A re-check that found nothing is not repeated until the evidence changes: an object seen that
  // the last one did not have (none within the memory's same_object_distance, odometry frame),
  // the tracked pose explaining a different count, or the tracking moving the pose against the
  // odometry by recheck_pose_shift / recheck_pose_turn. Re-checking the same objects frame after
  // frame was most of semantic-scanmatch's search CPU on the office floor. False:
  // every frame re-checks.
  bool recheck_on_new_evidence_only = true;
  double recheck_pose_shift = 0.1;
  double recheck_pose_turn = 0.05;
  // A pose the method stands by (a scan matcher's lock, a converged filter) is moved to another
  // place on the objects' word alone when that place explains at least this many more of the
  // objects seen during the turn (the laser fits look-alike places alike, and one object more
  // can be a confused class or a partial view); a lock moves for fewer only when the laser also
  // fits the other place better.
  int relocate_margin = 2;
  // When pre-localization decides between look-alike places (DecisionGate): the same place
  // standing out this many times with no look-alike tie between, and — after look-alike places
  // were left undecided with k objects explained — explaining more than k (forgotten after
  // memory.max_travel). 1 and false: every pre-localization decides on its own.
  int decision_confirmations = 2;
  bool decide_on_new_evidence = true;
  // The laser fit a decided place needs (DecisionGateOptions::min_laser_score).
  double decision_min_laser_score = 0.55;
  // Scan-to-map tracking once the robot is found (see the class comment).
  ScanTrackingOptions scan_tracking;
  // Seeds the filter's random stream.
  std::uint64_t seed = 1;
};

}  // namespace semchain::localization
