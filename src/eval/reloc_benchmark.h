#pragma once

#include <filesystem>
#include <functional>

#include "core/status.h"
#include "eval/reloc_benchmark_options.h"
#include "eval/reloc_results.h"
#include "eval/reloc_scoring.h"
#include "eval/reloc_trials.h"

// `semchain bench reloc` (DESIGN.md §4, seed 000 Tables 4–5, seed 001 Fig. 13/19): the map of a
// world is built from a simulated mapping run (SLAM and semantic mapping, not the truth); the
// robot is then put at random poses in the trial region of the live world (the same world, or
// a changed one), turns in place and moves off, and every method localizes from the same
// recordings. A trial succeeds when the estimate comes within 0.25 m and 10° of the truth and
// stays there to the end of the trial, within 30 s of simulated time.
namespace semchain::eval {

// Builds the map of 'world' from its mapping run, runs options.trials trials in 'live_world'
// and every method of options.methods on each, and scores them. 'progress' (may be empty) is
// called with (trials done, trials).
Result<RelocBenchmarkResult> RunRelocBenchmark(const std::filesystem::path& world,
                                               const std::filesystem::path& live_world,
                                               const RelocBenchmarkOptions& options,
                                               const std::function<void(int, int)>& progress = {});

}  // namespace semchain::eval
