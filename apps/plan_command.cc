// semchain plan --map MAP --from X,Y --to X,Y[;X,Y...] --out PATH.json [--keepout FILE.yaml]
//               [--robot-radius R] [--inflation-radius R] [--png PATH.png] ...
// Plans a route S → P1 → P2 … with A* on the inflated costmap of a map_server map (seed 004
// §3.2, DESIGN.md §3.9) and writes {"length_m", "cost", "path"} as JSON (DESIGN.md §4).
#include <spdlog/spdlog.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "apps/command.h"
#include "core/atomic_file.h"
#include "mapping/map_io.h"
#include "planning/costmap.h"
#include "planning/keepout.h"
#include "planning/path_io.h"
#include "planning/route.h"

namespace semchain::app {
namespace {

namespace fs = std::filesystem;

struct PlanArgs {
  std::string map;
  std::string from;
  std::vector<std::string> to;  // each X,Y[;X,Y...]
  std::string out;
  std::string keepout;
  std::string png;
  std::string unknown = "lethal";
  planning::CostmapOptions costmap;
  planning::AStarOptions astar;
};

// A finite number that fills all of 'text'.
bool ParseNumber(std::string_view text, double* value) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  if (text.empty()) return false;
  if (text.front() == '+') text.remove_prefix(1);
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), *value);
  return error == std::errc() && end == text.data() + text.size() && std::isfinite(*value);
}

// "X,Y" pairs separated by ';' (metres, map coordinates).
Result<std::vector<Eigen::Vector2d>> ParsePoints(const std::string& option,
                                                 const std::string& text) {
  std::vector<Eigen::Vector2d> points;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(';', begin), text.size());
    const std::string item = text.substr(begin, end - begin);
    const std::size_t comma = item.find(',');
    double x = 0.0, y = 0.0;
    if (comma == std::string::npos || !ParseNumber(std::string_view(item).substr(0, comma), &x) ||
        !ParseNumber(std::string_view(item).substr(comma + 1), &y)) {
      return Status::Error(option + ": '" + item + "' is not a point X,Y in metres");
    }
    points.emplace_back(x, y);
    begin = end + 1;
  }
  return points;
}

// MAP may be a map folder (MAP/map.yaml) or the YAML file itself.
fs::path MapYaml(const std::string& map) {
  return fs::is_directory(map) ? fs::path(map) / "map.yaml" : fs::path(map);
}

int RunPlanCommand(PlanArgs args) {
  args.costmap.unknown =
      args.unknown == "free" ? planning::UnknownPolicy::kFree : planning::UnknownPolicy::kLethal;
  Result<std::vector<Eigen::Vector2d>> waypoints = ParsePoints("--from", args.from);
  if (!waypoints.ok()) return ReportError(waypoints.status());
  if (waypoints->size() != 1) return ReportError(Status::Error("--from takes one point X,Y"));
  for (const std::string& to : args.to) {
    const Result<std::vector<Eigen::Vector2d>> goals = ParsePoints("--to", to);
    if (!goals.ok()) return ReportError(goals.status());
    waypoints->insert(waypoints->end(), goals->begin(), goals->end());
  }

  const Result<mapping::MapImage> map = mapping::ReadMap(MapYaml(args.map));
  if (!map.ok()) return ReportError(map.status());
  std::vector<planning::Polygon> zones;
  if (!args.keepout.empty()) {
    Result<std::vector<planning::Polygon>> read = planning::ReadKeepoutZones(args.keepout);
    if (!read.ok()) return ReportError(read.status());
    zones = std::move(*read);
  }
  const Result<planning::Costmap> costmap = planning::BuildCostmap(*map, zones, args.costmap);
  if (!costmap.ok()) return ReportError(costmap.status());
  const Result<planning::Route> route = planning::PlanRoute(*costmap, *waypoints, args.astar);
  if (!route.ok()) return ReportError(route.status());

  // The picture first: the route JSON appearing means that everything asked for was written.
  if (!args.png.empty()) {
    const Status png =
        planning::WriteRoutePng(args.png, planning::DrawRoute(*map, *costmap, *route));
    if (!png.ok()) return ReportError(png);
  }
  const Status written = planning::WriteRouteJson(args.out, *route);
  if (!written.ok()) return ReportError(written);
  spdlog::info("plan: {} goal(s), {:.2f} m, cost {:.2f}, {} noise cells removed",
               waypoints->size() - 1, route->length_meters, route->cost,
               costmap->removed_noise_cells);
  return 0;
}

}  // namespace

void AddPlanCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<PlanArgs>();
  CLI::App* command = app.add_subcommand(
      "plan", "A* route S -> P1 -> P2 ... on the inflated costmap of a map (seed 004)");
  command->add_option("--map", args->map, "Map folder (MAP/map.yaml) or map_server YAML")
      ->required();
  command->add_option("--from", args->from, "Start X,Y in map coordinates (metres)")->required();
  command
      ->add_option("--to", args->to,
                   "Goals X,Y[;X,Y...] (or several X,Y arguments), visited in order")
      ->required();
  command->add_option("--out", args->out, "Route JSON: {length_m, cost, path}")->required();
  command->add_option("--keepout", args->keepout, "YAML with keep-out polygons (keepout: [...])");
  command->add_option("--png", args->png, "Picture of the costmap with the route");
  command
      ->add_option("--robot-radius", args->costmap.robot_radius_meters,
                   "Robot radius, metres (cells closer to an obstacle are a collision)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--inflation-radius", args->costmap.inflation_radius_meters,
                   "Distance out to which obstacles raise the cost, metres")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--cost-scaling-factor", args->costmap.cost_scaling_factor,
                   "Decay rate of the inflation cost, 1/m (nav2's cost_scaling_factor)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command
      ->add_option("--cost-weight", args->astar.cost_weight,
                   "Step cost = length x (1 + weight x cell cost / 252)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--min-obstacle-cells", args->costmap.min_obstacle_cells,
                   "Occupied components smaller than this are noise and removed")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command->add_option("--unknown", args->unknown, "Unknown cells are lethal or free")
      ->capture_default_str()
      ->check(CLI::IsMember({"lethal", "free"}));
  command->callback([args, &exit_code] { exit_code = RunPlanCommand(*args); });
}

}  // namespace semchain::app
