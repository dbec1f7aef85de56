#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/status.h"
#include "mapping/occupancy_grid.h"

// Maps in the ROS map_server / nav2 format (DESIGN.md §5.3): a YAML file with image,
// resolution, origin, negate, occupied_thresh, free_thresh and mode, next to a PGM image whose
// first row is the top of the map (largest y).
namespace semchain::mapping {

// A map as map_server loads it: one value per cell, row-major with row 0 at the bottom
// (y = origin.y), as in nav_msgs/OccupancyGrid: -1 unknown, 0 free, 100 occupied ("scale" mode
// gives values in between).
struct MapImage {
  int width = 0;
  int height = 0;
  double resolution = 0.05;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // x, y, yaw of the lower-left corner
  bool negate = false;
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
  std::string mode = "trinary";  // trinary | scale | raw
  std::vector<std::int8_t> cells;

  std::int8_t At(int x, int y) const { return cells[static_cast<std::size_t>(y * width + x)]; }
  bool operator==(const MapImage& other) const = default;
};

// What a map.yaml may say: cells of 1 mm to 10 m, an origin within 1000 km.
inline constexpr double kMinMapResolution = 0.001;
inline constexpr double kMaxMapResolution = 10.0;
inline constexpr double kMaxMapOrigin = 1e6;

// Reads 'yaml_path' and the image it names (relative to the YAML's folder): binary or ASCII
// PGM, or any format OpenCV reads (PNG…). Errors name the file and, for YAML, the line.
Result<MapImage> ReadMap(const std::filesystem::path& yaml_path);

// Writes 'yaml_path' and, beside it, a binary PGM with the same stem (atomically, the image
// first). Trinary maps are written 0 = occupied, 254 = free, 205 = unknown, as map_saver does.
Status WriteMap(const std::filesystem::path& yaml_path, const MapImage& map);

// Thresholds a log-odds grid into a trinary map covering its observed cells plus 'margin'
// cells: occupied where P > occupied_thresh, free where P < free_thresh, else unknown.
MapImage GridToMapImage(const OccupancyGrid& grid, int margin_cells = 2);

// A grid for scan matching against a loaded map: occupied cells get 'occupied_log_odds'
// (hits at the cell centre), free cells the negative of it; unknown cells stay unobserved.
OccupancyGrid MapImageToGrid(const MapImage& map, double occupied_log_odds = 4.0);

// Writes a greyscale PNG of 'map' (white free, black occupied, grey unknown), top row = max y.
Status WriteMapPng(const std::filesystem::path& png_path, const MapImage& map);

}  // namespace semchain::mapping
