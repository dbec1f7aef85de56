#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "core/status.h"
#include "eval/reloc_benchmark_options.h"
#include "eval/reloc_methods.h"
#include "io/trajectory_io.h"
#include "sim/world.h"

// The trials of `semchain bench reloc`: where they start in the live world's trial region, and
// each trial's recording (simulated, or read back from a kept run).
namespace semchain::eval {

// Whether 'world' (read from 'source') has a trial region inside its walls' extent (the map can
// cover nothing else).
Status CheckTrialRegionInWorld(const sim::World& world, const std::string& source);

// 'count' uniform poses in the trial region of 'world', in free space at least 'clearance' from
// every surface, drawn with 'seed'; an error naming 'source' when none can be found.
Result<std::vector<Pose2>> RelocTrialStarts(const sim::World& world, int count, double clearance,
                                            std::uint64_t seed, const std::string& source);

// One trial as the benchmark makes it: the robot put at 'start' in 'world', turning
// options.trial_turns times and driving off up to options.trial_forward, simulated with 'seed'
// into the directory 'run'; what the methods get, and the truth at every scan.
struct RelocTrialRun {
  RelocRunInputs inputs;
  std::vector<StampedPose> truth;  // one per scan
};
Result<RelocTrialRun> SimulateRelocTrial(const sim::World& world, const Pose2& start,
                                         std::uint64_t seed, const RelocBenchmarkOptions& options,
                                         const std::filesystem::path& run);
// The same from a trial already simulated into 'run' (its log, detections, camera and truth).
Result<RelocTrialRun> LoadRelocTrial(std::uint64_t seed, const RelocBenchmarkOptions& options,
                                     const std::filesystem::path& run);

}  // namespace semchain::eval
