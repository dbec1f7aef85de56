#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <vector>

#include "core/status.h"

// Keep-out zones: areas the robot must not enter although the map shows them free (seed 004
// §3.2), as polygons in map coordinates. The file is YAML:
//   keepout:
//     - [[1.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 2.0]]   # metres, at least 3 vertices
namespace semchain::planning {

using Polygon = std::vector<Eigen::Vector2d>;

// Reads a keep-out file; errors name file, line and key ("zones.yaml:4: keepout[1][2]: ...").
Result<std::vector<Polygon>> ReadKeepoutZones(const std::filesystem::path& path);

}  // namespace semchain::planning
