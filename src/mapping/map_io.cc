#include "mapping/map_io.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include "core/atomic_file.h"
#include "drawing/png.h"
#include "io/yaml_reader.h"
#include "mapping/pgm_image.h"

namespace semchain::mapping {
namespace {

std::string FormatNumber(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

// Pixel values for occupied, free and unknown cells that map_server reads back as such.
struct TrinaryPixels {
  std::uint8_t occupied = 0, free = 254, unknown = 205;
};

TrinaryPixels PixelsFor(const MapImage& map) {
  TrinaryPixels pixels;
  const double unknown_occupancy = (255.0 - 205.0) / 255.0;
  if (!(unknown_occupancy > map.free_thresh && unknown_occupancy < map.occupied_thresh)) {
    const double middle = 0.5 * (map.free_thresh + map.occupied_thresh);
    pixels.unknown = static_cast<std::uint8_t>(std::lround(255.0 * (1.0 - middle)));
  }
  if (map.negate) {
    pixels.occupied = static_cast<std::uint8_t>(255 - pixels.occupied);
    pixels.free = static_cast<std::uint8_t>(255 - pixels.free);
    pixels.unknown = static_cast<std::uint8_t>(255 - pixels.unknown);
  }
  return pixels;
}

std::uint8_t CellToPixel(const MapImage& map, const TrinaryPixels& pixels, std::int8_t value) {
  if (map.mode == "raw") return static_cast<std::uint8_t>(value < 0 ? 255 : value);
  if (value < 0) return pixels.unknown;
  if (map.mode == "scale") {  // nav2 map_saver: 255 - 2.55 × value, negated if asked
    const auto pixel = static_cast<std::uint8_t>(std::lround(255.0 - 2.55 * value));
    return map.negate ? static_cast<std::uint8_t>(255 - pixel) : pixel;
  }
  if (value >= 100 * map.occupied_thresh) return pixels.occupied;
  if (value <= 100 * map.free_thresh) return pixels.free;
  return pixels.unknown;
}

// map_server's reading of one pixel (mean of its channels).
std::int8_t PixelToCell(const MapImage& map, double pixel) {
  if (map.mode == "raw") return pixel <= 100.0 ? static_cast<std::int8_t>(pixel) : -1;
  const double occupancy = map.negate ? pixel / 255.0 : (255.0 - pixel) / 255.0;
  if (occupancy > map.occupied_thresh) return 100;
  if (occupancy < map.free_thresh) return 0;
  if (map.mode == "trinary") return -1;
  return static_cast<std::int8_t>(
      std::lround(99.0 * (occupancy - map.free_thresh) / (map.occupied_thresh - map.free_thresh)));
}

Status ReadYamlFields(const yaml::Node& root, MapImage* map, std::string* image) {
  SEMCHAIN_RETURN_IF_ERROR(root.CheckKeys(
      {"image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh", "mode"}));
  for (const char* key : {"image", "resolution", "origin", "occupied_thresh", "free_thresh"}) {
    if (!root.Has(key)) return root.Error(std::string("missing key '") + key + "'");
  }
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(root, "image", image));
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(root, "resolution", &map->resolution));
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(root, "occupied_thresh", &map->occupied_thresh));
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(root, "free_thresh", &map->free_thresh));
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(root, "mode", &map->mode));
  std::vector<double> origin;
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(root, "origin", &origin));
  if (origin.size() != 3) return root.Error("origin: expected [x, y, yaw]");
  map->origin = Eigen::Vector3d(origin[0], origin[1], origin[2]);
  int negate = 0;
  if (root.Has("negate")) {
    const Result<yaml::Node> node = root.Get("negate");
    const Result<int> as_int = node->AsInt();
    const Result<bool> as_bool = node->AsBool();
    if (!as_int.ok() && !as_bool.ok()) return as_int.status();
    negate = as_int.ok() ? *as_int : static_cast<int>(*as_bool);
  }
  map->negate = negate != 0;
  // The grids behind a map take (0, 10] m cells (OccupancyGridOptions); below 1 mm or beyond
  // 1000 km from the origin, cell indices of points on the map would overflow an int.
  if (!(map->resolution >= kMinMapResolution && map->resolution <= kMaxMapResolution)) {
    return root.Error("resolution must be in [" + FormatNumber(kMinMapResolution) + ", " +
                      FormatNumber(kMaxMapResolution) + "] m");
  }
  if (!(std::abs(map->origin.x()) <= kMaxMapOrigin && std::abs(map->origin.y()) <= kMaxMapOrigin)) {
    return root.Error("origin: x and y must be within " + FormatNumber(kMaxMapOrigin / 1000) +
                      " km");
  }
  if (!(map->free_thresh >= 0.0 && map->free_thresh < map->occupied_thresh &&
        map->occupied_thresh <= 1.0)) {
    return root.Error("need 0 <= free_thresh < occupied_thresh <= 1");
  }
  if (map->mode != "trinary" && map->mode != "scale" && map->mode != "raw") {
    return root.Error("mode must be trinary, scale or raw, not '" + map->mode + "'");
  }
  return Status::Ok();
}

}  // namespace

Result<MapImage> ReadMap(const std::filesystem::path& yaml_path) {
  const Result<yaml::Node> root = yaml::Node::LoadFile(yaml_path);
  if (!root.ok()) return root.status();
  MapImage map;
  std::string image_name;
  SEMCHAIN_RETURN_IF_ERROR(ReadYamlFields(*root, &map, &image_name));
  std::filesystem::path image_path(image_name);
  if (image_path.is_relative()) image_path = yaml_path.parent_path() / image_path;
  const Result<GrayImage> image = ReadGrayImage(image_path);
  if (!image.ok()) return image.status();
  map.width = image->width;
  map.height = image->height;
  map.cells.resize(static_cast<std::size_t>(map.width) * map.height);
  for (int row = 0; row < map.height; ++row) {
    for (int x = 0; x < map.width; ++x) {
      const int y = map.height - 1 - row;  // the image's first row is the top
      map.cells[static_cast<std::size_t>(y * map.width + x)] =
          PixelToCell(map, image->pixels[static_cast<std::size_t>(row * map.width + x)]);
    }
  }
  return map;
}

Status WriteMap(const std::filesystem::path& yaml_path, const MapImage& map) {
  SEMCHAIN_CHECK(map.cells.size() == static_cast<std::size_t>(map.width) * map.height);
  std::filesystem::path image_path = yaml_path;
  image_path.replace_extension(".pgm");
  std::vector<std::uint8_t> image(map.cells.size());
  const TrinaryPixels pixels = PixelsFor(map);
  for (int row = 0; row < map.height; ++row) {
    for (int x = 0; x < map.width; ++x) {
      image[static_cast<std::size_t>(row * map.width + x)] =
          CellToPixel(map, pixels, map.At(x, map.height - 1 - row));
    }
  }
  SEMCHAIN_RETURN_IF_ERROR(WritePgm(image_path, map.width, map.height, image, map.resolution));
  std::ostringstream yaml;
  yaml << "image: " << image_path.filename().string() << "\n"
       << "mode: " << map.mode << "\n"
       << "resolution: " << FormatNumber(map.resolution) << "\n"
       << "origin: [" << FormatNumber(map.origin.x()) << ", " << FormatNumber(map.origin.y())
       << ", " << FormatNumber(map.origin.z()) << "]\n"
       << "negate: " << (map.negate ? 1 : 0) << "\n"
       << "occupied_thresh: " << FormatNumber(map.occupied_thresh) << "\n"
       << "free_thresh: " << FormatNumber(map.free_thresh) << "\n";
  return WriteFileAtomically(yaml_path, yaml.str());
}

MapImage GridToMapImage(const OccupancyGrid& grid, int margin_cells) {
  MapImage map;
  map.resolution = grid.resolution();
  CellBox box = grid.KnownBounds();
  if (box.empty()) box.min = box.max = Eigen::Vector2i::Zero();
  box.min.array() -= margin_cells;
  box.max.array() += margin_cells;
  map.width = box.width();
  map.height = box.height();
  const Eigen::Vector2d corner = grid.origin() + box.min.cast<double>() * grid.resolution();
  map.origin = Eigen::Vector3d(corner.x(), corner.y(), 0.0);
  map.cells.assign(static_cast<std::size_t>(map.width) * map.height, -1);
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      const GridCell* cell = grid.Find(box.min + Eigen::Vector2i(x, y));
      if (cell == nullptr || !cell->Known()) continue;
      const double p = LogOddsToProbability(cell->log_odds);
      std::int8_t& out = map.cells[static_cast<std::size_t>(y * map.width + x)];
      if (p > map.occupied_thresh) out = 100;
      if (p < map.free_thresh) out = 0;
    }
  }
  return map;
}

OccupancyGrid MapImageToGrid(const MapImage& map, double occupied_log_odds) {
  OccupancyGridOptions options;
  options.resolution_meters = map.resolution;
  options.max_abs_log_odds = std::max(options.max_abs_log_odds, occupied_log_odds);
  OccupancyGrid grid(options, map.origin.head<2>());
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      const std::int8_t value = map.At(x, y);
      if (value < 0) continue;
      GridCell cell;
      cell.observations = 1;
      const double p = std::clamp(value / 100.0, 0.001, 0.999);
      cell.log_odds = static_cast<float>(
          std::clamp(ProbabilityToLogOdds(p), -occupied_log_odds, occupied_log_odds));
      cell.hits = value >= 100 * map.occupied_thresh ? 1 : 0;
      grid.SetCell({x, y}, cell);
    }
  }
  return grid;
}

Status WriteMapPng(const std::filesystem::path& png_path, const MapImage& map) {
  cv::Mat image(map.height, map.width, CV_8UC1);
  const TrinaryPixels pixels{0, 254, 205};
  const MapImage plain{map.width,           map.height,      map.resolution, map.origin, false,
                       map.occupied_thresh, map.free_thresh, "trinary",      {}};
  for (int row = 0; row < map.height; ++row) {
    for (int x = 0; x < map.width; ++x) {
      image.at<std::uint8_t>(row, x) = CellToPixel(plain, pixels, map.At(x, map.height - 1 - row));
    }
  }
  return drawing::WritePng(image, png_path);
}

}  // namespace semchain::mapping
