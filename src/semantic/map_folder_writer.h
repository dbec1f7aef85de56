#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/status.h"
#include "io/trajectory_io.h"
#include "mapping/map_io.h"
#include "semantic/keyframes.h"
#include "semantic/semantic_map.h"

// Writes a complete semchain map folder (what ReadMapFolder reads) so that nobody ever sees a
// half-written one: `slam --semantic` and the ROS node's mapping mode write through it.
namespace semchain::semantic {

struct MapFolderContents {
  mapping::MapImage occupancy;                  // map.yaml + map.pgm
  std::vector<StampedPose> trajectory;          // trajectory.txt
  const SemanticMap* semantic = nullptr;        // semantic.json (none when null)
  const KeyframeDatabase* keyframes = nullptr;  // keyframes.json (none when null)
};

// Writes 'contents' into a staging folder beside 'out', lets 'extra' (may be empty) add more
// files to it (it gets the staging folder), then renames the staging folder to 'out',
// replacing a previous 'out' as a whole. On any error 'out' is left as it was and the staging
// folder removed; the error names the file or folder.
Status WriteMapFolder(const std::filesystem::path& out, const MapFolderContents& contents,
                      const std::function<Status(const std::filesystem::path&)>& extra = {});

}  // namespace semchain::semantic
