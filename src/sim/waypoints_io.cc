// Route files for `simulate --route FILE` (LoadWaypoints in world_io.h).
#include <sstream>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "io/yaml_reader.h"
#include "sim/world_io.h"
#include "sim/world_io_internal.h"

namespace semchain::sim {
namespace {

bool IsYaml(const std::filesystem::path& path) {
  const std::string extension = path.extension().string();
  return extension == ".yaml" || extension == ".yml";
}

// "x y" or "x, y" per line; blank lines and '#' comments are skipped.
Result<std::vector<Eigen::Vector2d>> ParseTextWaypoints(const std::string& text,
                                                        const std::string& source) {
  std::vector<Eigen::Vector2d> points;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    line = line.substr(0, line.find('#'));
    for (char& c : line) c = c == ',' ? ' ' : c;
    std::istringstream fields(line);
    std::string first;
    if (!(fields >> first)) continue;
    fields.clear();
    fields.seekg(0);
    double x = 0.0, y = 0.0;
    std::string extra;
    if (!(fields >> x >> y) || (fields >> extra) || !std::isfinite(x) || !std::isfinite(y)) {
      return Status::Error(source + ":" + std::to_string(number) +
                           ": expected a waypoint \"x y\" in metres, got '" + line + "'");
    }
    points.emplace_back(x, y);
  }
  if (points.empty()) return Status::Error(source + ": no waypoints");
  return points;
}

}  // namespace

Result<std::vector<Eigen::Vector2d>> LoadWaypoints(const std::filesystem::path& path) {
  if (!IsYaml(path)) {
    Result<std::string> text = ReadFile(path);
    if (!text.ok()) return text.status();
    return ParseTextWaypoints(*text, path.string());
  }
  Result<yaml::Node> root = yaml::Node::LoadFile(path);
  if (!root.ok()) return root.status();
  std::vector<Eigen::Vector2d> points;
  SEMCHAIN_RETURN_IF_ERROR(internal::ParsePointList(*root, 1, "a route", &points));
  return points;
}

}  // namespace semchain::sim
