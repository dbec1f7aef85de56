#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "core/status.h"
#include "localization/reloc_trace.h"
#include "mapping/map_io.h"
#include "semantic/semantic_map.h"

namespace semchain::app {

// What `semchain localize --png` shows besides the map and the method's trace.
struct RelocPictureOptions {
  std::string method;  // named in the picture's title
  // The timestamp of each scan of the run; times in the picture count from the first.
  std::vector<double> scan_times;
  std::vector<Pose2> truth;  // the run's true trajectory (RUN/truth.txt); may be empty
  int max_snapshots = 6;     // particle clouds drawn, at most (first, pre-localized, last, ...)
  // The map's longer side is drawn this long (so that a cell is several pixels and particle
  // clouds stay visible on big and small maps alike).
  int long_side_px = 1000;
};

// The particle snapshots drawn: the first, the first at or after 'prelocalization_scan' (when
// it is ≥ 0), the last, and others evenly spread between them; at most 'max_count', in order.
std::vector<std::size_t> SelectSnapshots(
    const std::vector<localization::ParticleSnapshot>& snapshots, int prelocalization_scan,
    int max_count);

// Draws a relocalization top-down and writes it as a PNG, atomically: the occupancy map in
// grey with the semantic objects and chains, the particle clouds of SelectSnapshots (old light,
// latest strong, their times in the legend), the pre-localization's best hypothesis, where a
// scan matcher found the robot, the true trajectory and the final estimate as arrows. The map
// must not be rotated (origin θ = 0).
Status WriteRelocalizationPng(const mapping::MapImage& map, const semantic::SemanticMap& semantic,
                              const localization::RelocTrace& trace,
                              const RelocPictureOptions& options,
                              const std::filesystem::path& path);

}  // namespace semchain::app
