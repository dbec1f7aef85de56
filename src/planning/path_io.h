#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/status.h"
#include "mapping/map_io.h"
#include "planning/costmap.h"
#include "planning/route.h"

// What `semchain plan` writes: the route as JSON (DESIGN.md §4) and drawn on the map.
namespace semchain::planning {

// {"length_m": L, "cost": C, "path": [[x, y], ...]} in map coordinates (metres).
std::string RouteJson(const Route& route);
Status WriteRouteJson(const std::filesystem::path& path, const Route& route);

// A colour picture of 'map' (white free, black occupied, grey unknown, top row = largest y) with
// the costmap's inflation shaded blue, keep-out zones red, the route as a blue line, the start
// green and each goal red. Each cell is drawn 'pixels_per_cell' pixels wide (0: chosen so that
// the image is about 800 pixels wide, 1 to 8).
cv::Mat DrawRoute(const mapping::MapImage& map, const Costmap& costmap, const Route& route,
                  int pixels_per_cell = 0);
Status WriteRoutePng(const std::filesystem::path& path, const cv::Mat& image);

}  // namespace semchain::planning
