#pragma once

#include <nav_msgs/OccupancyGrid.h>

#include <string>

#include "mapping/map_io.h"

namespace semchain::ros1 {

// The map as nav_msgs/OccupancyGrid: MapImage holds the same cell values (-1 unknown, 0 free,
// 100 occupied) in the same order (row 0 at the origin's y).
nav_msgs::OccupancyGrid ToOccupancyGridMsg(const mapping::MapImage& map,
                                           const std::string& frame_id);

}  // namespace semchain::ros1
