// semchain simulate --world W.yaml --out RUN [--seed N] [--route mapping|trial|FILE]
//                   [--start X,Y,THETA] [--no-frames]
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "apps/command.h"
#include "apps/shipped_file.h"
#include "core/atomic_file.h"
#include "sim/simulator.h"
#include "sim/world.h"
#include "sim/world_io.h"

namespace semchain::app {
namespace {

struct SimulateArgs {
  std::string world;
  std::string out;
  std::uint64_t seed = 0;
  std::string route = "mapping";
  std::vector<double> start;  // x, y, θ; empty: the world's robot.start
  bool no_frames = false;
};

Result<sim::RouteSpec> ParseRoute(const std::string& text) {
  sim::RouteSpec route;
  if (text == "mapping") return route;
  if (text == "trial") {
    route.kind = sim::RouteSpec::Kind::kTrial;
    return route;
  }
  if (!std::filesystem::is_regular_file(text)) {
    return Status::Error("--route: '" + text + "' is neither mapping, trial nor a waypoint file");
  }
  Result<std::vector<Eigen::Vector2d>> waypoints = sim::LoadWaypoints(text);
  if (!waypoints.ok()) return waypoints.status();
  route.kind = sim::RouteSpec::Kind::kWaypoints;
  route.waypoints = std::move(*waypoints);
  return route;
}

Status RunSimulate(const SimulateArgs& args) {
  // The text is read once: parsed here, and copied into the run as RUN/world.yaml.
  Result<std::string> world_yaml = ReadFile(args.world);
  if (!world_yaml.ok()) return world_yaml.status();
  Result<sim::World> world = sim::ParseWorld(*world_yaml, args.world);
  if (!world.ok()) return world.status();
  SEMCHAIN_RETURN_IF_ERROR(sim::ValidateWorld(*world, args.world));
  Result<sim::RouteSpec> route = ParseRoute(args.route);
  if (!route.ok()) return route.status();
  sim::SimulationOptions options;
  options.seed = args.seed;
  options.route = *route;
  if (!args.start.empty()) options.start = Pose2(args.start[0], args.start[1], args.start[2]);
  options.write_frames = !args.no_frames;
  options.world_yaml = std::move(*world_yaml);
  SEMCHAIN_RETURN_IF_ERROR(sim::Simulate(*world, options, args.out));
  std::printf("wrote %s\n", args.out.c_str());
  return Status::Ok();
}

}  // namespace

void AddSimulateCommand(CLI::App& app, int& exit_code) {
  CLI::App* command = app.add_subcommand(
      "simulate",
      "Drive a simulated robot through a world and write a run directory: a CARMEN log "
      "(log.clf), the true poses (truth.txt), RGB-D frames, detections and camera.yaml");
  auto args = std::make_shared<SimulateArgs>();
  command->add_option("--world", args->world, "World file (YAML, DESIGN.md section 5.2)")
      ->required()
      ->transform(ShippedFile());
  command->add_option("--out", args->out, "Run directory to write (replaces an earlier run)")
      ->required();
  command
      ->add_option("--seed", args->seed,
                   "Seed of every noise source (lidar, odometry, "
                   "detections); the same seed gives the same bytes")
      ->capture_default_str();
  command
      ->add_option("--route", args->route,
                   "mapping (the world's mapping_route), trial (rotate in place, then drive "
                   "ahead) or a file of waypoints (YAML list of [x, y], or 'x y' per line)")
      ->capture_default_str();
  command
      ->add_option("--start", args->start,
                   "Start pose X,Y,THETA (metres, radians; the world's robot.start by default), "
                   "e.g. a trial in the trial region")
      ->expected(3)
      ->delimiter(',');
  command->add_flag("--no-frames", args->no_frames, "Write no frames and no detections");
  command->callback([args, &exit_code] {
    const Status status = RunSimulate(*args);
    exit_code = status.ok() ? 0 : ReportError(status);
  });
}

}  // namespace semchain::app
