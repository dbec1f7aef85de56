#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include "bow/keyframe_recognizer.h"
#include "core/status.h"
#include "eval/reloc_benchmark_options.h"
#include "io/trajectory_io.h"
#include "mapping/map_io.h"
#include "semantic/keyframes.h"
#include "semantic/semantic_map.h"
#include "sim/world.h"

// The map `semchain bench reloc` localizes on: a simulated mapping run's SLAM map and semantic
// map (not the truth), built or read back from a kept run, and its bag of words.
namespace semchain::eval {

// What the mapping run gives the trials.
struct RelocBuiltMap {
  mapping::MapImage occupancy;
  semantic::SemanticMap semantic;
  std::vector<semantic::Keyframe> keyframes;
  double ate = 0.0;                     // the SLAM trajectory against the run's truth
  std::vector<StampedPose> trajectory;  // the mapping run's SLAM estimate
};

// Simulates the mapping run of 'world' into 'run' (options.seed) and maps it: SLAM, then the
// semantic map on the SLAM trajectory (options.detect's detections when given).
Result<RelocBuiltMap> BuildRelocMap(const sim::World& world, const RelocBenchmarkOptions& options,
                                    const std::filesystem::path& run);
// The map as kept in RUN/map: map.yaml, semantic.json, keyframes.json, trajectory.txt, ate.json.
Status WriteRelocMap(const RelocBuiltMap& built, const std::filesystem::path& run);
// The map WriteRelocMap kept in 'run' (a trajectory missing from an older one is made again by
// the SLAM with 'seed').
Result<RelocBuiltMap> ReadRelocMap(const std::filesystem::path& run, std::uint64_t seed);

// The bag of words of the mapping run in 'run' (seed 000 §3.1 steps 1–2): a vocabulary trained
// on its frames with 'seed' and its keyframes described with it.
Result<std::shared_ptr<const bow::KeyframeRecognizer>> BuildRelocRecognizer(
    const RelocBuiltMap& built, const std::filesystem::path& run, std::uint64_t seed);

}  // namespace semchain::eval
