#pragma once

#include <filesystem>

#include "core/status.h"
#include "mapping/map_io.h"
#include "semantic/semantic_map.h"

// A semchain map folder as `slam` and `semantic` write it: map.yaml (+ its image), semantic.json
// and, when the semantic mapping kept them, keyframes.json.
namespace semchain::semantic {

struct MapFolder {
  mapping::MapImage occupancy;
  SemanticMap semantic;
  std::filesystem::path keyframes;  // DIR/keyframes.json (may not exist)
};

// Reads DIR/map.yaml and DIR/semantic.json; an object outside the map's extent is an error (the
// two files were made for different maps).
Result<MapFolder> ReadMapFolder(const std::filesystem::path& dir);

}  // namespace semchain::semantic
