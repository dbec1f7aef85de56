#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/status.h"
#include "localization/localizer.h"
#include "localization/prelocalization_options.h"
#include "sensors/detection.h"

// What `semchain bench reloc` (reloc_benchmark.h) runs: the trials, their behaviour and the
// success tolerances, how the methods are set up, where the runs are kept.
namespace semchain::eval {

struct RelocBenchmarkOptions {
  int trials = 35;
  std::uint64_t seed = 1;
  std::vector<std::string> methods = {"amcl", "semantic-amcl", "semantic-amcl-bow",
                                      "semantic-scanmatch", "scanmatch-global"};
  double success_distance = 0.25;   // metres
  double success_heading = 0.1745;  // radians (10°)
  double time_limit = 30.0;         // seconds of simulated time
  // Trial starts keep this far (metres) from any wall or object.
  double start_clearance = 0.25;
  // The trial behaviour: turns in place, then a drive of at most this far.
  double trial_turns = 2.0;
  double trial_forward = 1.0;
  // Active relocalization (off: the protocol of docs/results.md's tables): the drive goes towards
  // the most open heading, and the robot turns in place this many times where it ended
  // (sim::TrialOptions::face_most_open, rotation_after_radians).
  bool trial_face_open = false;
  double trial_turns_after = 0.0;
  // How the semantic methods use the camera (observation memory, single-object hypotheses).
  localization::LocalizerOptions method;
  // How the objects pre-localize (laser refinement of the hypotheses, look-alike margins, ...).
  localization::PreLocalizationOptions prelocalization;
  // Where the runs are made (removed afterwards); a temporary directory when empty.
  std::filesystem::path work_dir;
  // Keep the runs in work_dir (the mapping run with its map in mapping/map/, each trial's
  // recording in trial_K/), and reuse those an earlier call kept there for the same worlds,
  // seed, trial settings and detections: methods can be compared again, and a failed trial
  // replayed with `semchain localize`, without simulating anything anew.
  bool keep_runs = false;
  // Detects the objects in a run's rendered frames (the mapping run's and every trial's), e.g.
  // an ONNX detector; empty: the simulator's detection model (RUN/detections.jsonl).
  std::function<Result<std::vector<FrameDetections>>(const std::filesystem::path& run)> detect;
  // Names the source of the detections in the results ("simulator" when 'detect' is empty).
  std::string detections_source = "simulator";
};

}  // namespace semchain::eval
