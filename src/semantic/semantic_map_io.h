#pragma once

#include <filesystem>
#include <string>

#include "core/status.h"
#include "semantic/semantic_map.h"

// semantic.json (DESIGN.md §5.4):
//   {"version": 1, "frame": "map", "classes": [...],
//    "objects": [{"id", "class", "center": [x, y], "footprint": [[x, y], ...], "observations",
//                 "confidence"}],
//    "chains": [{"region", "order": [ids], "links": [{"from", "to", "distance"}]}],
//    "neighbours": [{"from", "to", "distance"}]}
namespace semchain::semantic {

std::string FormatSemanticJson(const SemanticMap& map);
Status WriteSemanticJson(const std::filesystem::path& path, const SemanticMap& map);

// Reads and checks a semantic.json: every field of §5.4, unique object ids, classes from
// "classes", chains and neighbours naming existing objects, finite numbers. Errors name the
// file and the field: "map/semantic.json: objects[2].center: expected 2 numbers".
Result<SemanticMap> ReadSemanticJson(const std::filesystem::path& path);

}  // namespace semchain::semantic
