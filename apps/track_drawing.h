#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/status.h"
#include "eval/reference_check.h"
#include "eval/track_benchmark.h"

namespace semchain::app {

// Draws a tracking run's error over time (`bench track`): position error (m) above, heading
// error (deg) below, against log seconds from the first scan; in grey under each, the map's own
// inconsistency at that scan (the reference pose against the scan's best fit in the map,
// eval::ReferenceCheck), which the tracker cannot be expected to beat. Dashed lines mark the
// tracking targets 'target_m' and 'target_deg'.
Status WriteTrackPng(const std::string& title, const std::vector<eval::TrackedScan>& track,
                     const std::vector<eval::ReferenceCheck>& reference, double target_m,
                     double target_deg, const std::filesystem::path& path);

}  // namespace semchain::app
