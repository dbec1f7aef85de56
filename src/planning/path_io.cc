#include "planning/path_io.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "core/atomic_file.h"
#include "drawing/png.h"

namespace semchain::planning {
namespace {

// The BGR colour of a cell: the map's grey, tinted by the costmap.
cv::Vec3b CellColour(const mapping::MapImage& map, const Costmap& costmap, int x, int y) {
  const std::int8_t value = map.At(x, y);
  const double occupied = 100.0 * map.occupied_thresh;
  std::uint8_t grey = value < 0 ? 205 : (value >= occupied ? 0 : 254);
  cv::Vec3b colour(grey, grey, grey);
  const Eigen::Vector2i cell(x, y);
  if (costmap.InKeepout(cell)) return {90, 90, 230};
  const std::uint8_t cost = costmap.At(cell);
  if (grey == 254 && cost > kFreeCost && cost < kUnknownCost) {
    // Inflation: from light blue (low cost) to dark blue at the inscribed radius.
    const double t = std::min(1.0, cost / static_cast<double>(kInscribedCost));
    colour =
        cv::Vec3b(static_cast<std::uint8_t>(255 - 60 * t), static_cast<std::uint8_t>(240 - 130 * t),
                  static_cast<std::uint8_t>(220 - 150 * t));
  }
  return colour;
}

}  // namespace

std::string RouteJson(const Route& route) {
  nlohmann::json path = nlohmann::json::array();
  for (const Eigen::Vector2d& p : route.points) path.push_back({p.x(), p.y()});
  const nlohmann::json json = {
      {"length_m", route.length_meters}, {"cost", route.cost}, {"path", path}};
  return json.dump() + "\n";
}

Status WriteRouteJson(const std::filesystem::path& path, const Route& route) {
  return WriteFileAtomically(path, RouteJson(route));
}

cv::Mat DrawRoute(const mapping::MapImage& map, const Costmap& costmap, const Route& route,
                  int pixels_per_cell) {
  const int scale = pixels_per_cell > 0 ? pixels_per_cell : std::clamp(800 / map.width, 1, 8);
  cv::Mat cells(map.height, map.width, CV_8UC3);
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      cells.at<cv::Vec3b>(map.height - 1 - y, x) = CellColour(map, costmap, x, y);
    }
  }
  cv::Mat image;
  cv::resize(cells, image, cv::Size(), scale, scale, cv::INTER_NEAREST);
  const auto pixel = [&](const Eigen::Vector2d& p) {
    const Eigen::Vector2d cell = (p - costmap.origin) / costmap.resolution;
    return cv::Point(static_cast<int>(std::lround(cell.x() * scale)),
                     static_cast<int>(std::lround((map.height - cell.y()) * scale)));
  };
  std::vector<cv::Point> line;
  for (const Eigen::Vector2d& p : route.points) line.push_back(pixel(p));
  const int thickness = std::max(1, scale / 2);
  cv::polylines(image, line, false, cv::Scalar(200, 60, 0), thickness, cv::LINE_AA);
  const int radius = std::max(3, scale);
  if (!route.points.empty()) {
    cv::circle(image, line.front(), radius, cv::Scalar(0, 160, 0), cv::FILLED, cv::LINE_AA);
  }
  for (const std::size_t end : route.leg_ends) {
    cv::circle(image, line[end], radius, cv::Scalar(0, 0, 220), cv::FILLED, cv::LINE_AA);
  }
  return image;
}

Status WriteRoutePng(const std::filesystem::path& path, const cv::Mat& image) {
  return drawing::WritePng(image, path);
}

}  // namespace semchain::planning
