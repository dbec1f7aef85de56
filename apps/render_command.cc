// semchain render INPUT --out IMAGE.png [--scale PX_PER_M] [--world W.yaml] [--max-scans N]
// INPUT is a world file, a run directory (`semchain simulate`) or a map directory (`semchain
// slam`), drawn top-down with a legend; or a data set (`semchain dataset`), drawn as a grid of
// its frames with their label boxes.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "apps/command.h"
#include "apps/dataset_drawing.h"
#include "apps/map_grey.h"
#include "apps/semantic_drawing.h"
#include "apps/shipped_file.h"
#include "drawing/canvas.h"
#include "drawing/plots.h"
#include "drawing/png.h"
#include "io/carmen.h"
#include "io/trajectory_io.h"
#include "mapping/map_io.h"
#include "semantic/semantic_map_io.h"
#include "sim/world.h"
#include "sim/world_drawing.h"

namespace semchain::app {
namespace {

namespace fs = std::filesystem;

constexpr drawing::Color kTruthColor = {0, 160, 60};
constexpr drawing::Color kOdometryColor = {220, 40, 40};
constexpr drawing::Color kScanColor = {200, 0, 200};
constexpr drawing::Color kSlamColor = {0, 150, 160};

struct RenderArgs {
  std::string input;
  std::string out;
  double scale = 50.0;
  std::string world;  // optional overlay; a run's own world.yaml when present
  int max_scans = 200;
  std::string split = "train";  // a data set's
  int frames = 12;
};

// What a picture shows, gathered from the input before any drawing (so the canvas fits it).
struct Picture {
  std::optional<sim::World> world;
  std::optional<mapping::MapImage> map;
  std::vector<Pose2> truth, odometry, slam;
  std::vector<Eigen::Vector2d> scan_points;
  std::optional<semantic::SemanticMap> semantic;  // a map directory's semantic.json
};

// The pose at 'time' on a trajectory sorted by time (linear between samples, clamped).
Pose2 PoseAt(const std::vector<StampedPose>& poses, double time) {
  const auto after =
      std::lower_bound(poses.begin(), poses.end(), time,
                       [](const StampedPose& p, double t) { return p.timestamp < t; });
  if (after == poses.begin()) return poses.front().pose;
  if (after == poses.end()) return poses.back().pose;
  const StampedPose& before = *(after - 1);
  const double span = after->timestamp - before.timestamp;
  return Interpolate(before.pose, after->pose, span > 0.0 ? (time - before.timestamp) / span : 0.0);
}

// Laser returns of at most 'max_scans' evenly spread scans, in the world frame: placed with
// the true pose when there is one (so they line up with the world), else with odometry.
std::vector<Eigen::Vector2d> ScanPoints(const carmen::Log& log,
                                        const std::vector<StampedPose>& truth, int max_scans) {
  const std::vector<const carmen::Laser*> lasers = log.Lasers();
  std::vector<Eigen::Vector2d> points;
  if (lasers.empty() || max_scans <= 0) return points;
  const std::size_t step = (lasers.size() + max_scans - 1) / static_cast<std::size_t>(max_scans);
  for (std::size_t i = 0; i < lasers.size(); i += step) {
    const StampedScan& stamped = lasers[i]->scan;
    const Pose2 laser = truth.empty()
                            ? stamped.laser_pose
                            : PoseAt(truth, stamped.scan.timestamp) * stamped.LaserOffset();
    for (std::size_t b = 0; b < stamped.scan.size(); ++b) {
      if (!stamped.scan.IsReturn(b)) continue;
      const double angle = stamped.scan.BeamAngle(b), range = stamped.scan.ranges[b];
      points.push_back(laser * Eigen::Vector2d(range * std::cos(angle), range * std::sin(angle)));
    }
  }
  return points;
}

Status LoadOverlayWorld(const std::string& path, Picture& picture) {
  if (path.empty()) return Status::Ok();
  Result<sim::World> world = sim::LoadWorld(path);
  if (!world.ok()) return world.status();
  picture.world = std::move(*world);
  return Status::Ok();
}

Status ReadRun(const fs::path& dir, const RenderArgs& args, Picture& picture) {
  const fs::path log_path = fs::exists(dir / "log.clf") ? dir / "log.clf" : dir / "log.clf.gz";
  Result<carmen::Log> log = carmen::ReadLog(log_path);
  if (!log.ok()) return log.status();
  std::vector<StampedPose> truth;
  if (fs::exists(dir / "truth.txt")) {
    Result<std::vector<StampedPose>> read = ReadTrajectory(dir / "truth.txt");
    if (!read.ok()) return read.status();
    truth = std::move(*read);
  } else {
    for (const carmen::TruePose* p : log->TruePoses())
      truth.push_back({p->stamp.timestamp, p->truth});
  }
  std::sort(truth.begin(), truth.end(),
            [](const StampedPose& a, const StampedPose& b) { return a.timestamp < b.timestamp; });
  for (const StampedPose& p : truth) picture.truth.push_back(p.pose);
  for (const carmen::Odometry* odometry : log->Odometries())
    picture.odometry.push_back(odometry->pose);
  if (picture.odometry.empty()) {
    for (const carmen::Laser* laser : log->Lasers())
      picture.odometry.push_back(laser->scan.odometry);
  }
  picture.scan_points = ScanPoints(*log, truth, args.max_scans);
  const std::string world = !args.world.empty()              ? args.world
                            : fs::exists(dir / "world.yaml") ? (dir / "world.yaml").string()
                                                             : std::string();
  return LoadOverlayWorld(world, picture);
}

Status ReadMapDirectory(const fs::path& dir, const RenderArgs& args, Picture& picture) {
  Result<mapping::MapImage> map = mapping::ReadMap(dir / "map.yaml");
  if (!map.ok()) return map.status();
  if (map->origin.z() != 0.0) {
    return Status::Error((dir / "map.yaml").string() + ": rotated map origins are not supported");
  }
  picture.map = std::move(*map);
  if (fs::exists(dir / "semantic.json")) {
    Result<semantic::SemanticMap> objects = semantic::ReadSemanticJson(dir / "semantic.json");
    if (!objects.ok()) return objects.status();
    picture.semantic = std::move(*objects);
  }
  if (fs::exists(dir / "trajectory.txt")) {
    Result<std::vector<StampedPose>> slam = ReadTrajectory(dir / "trajectory.txt");
    if (!slam.ok()) return slam.status();
    for (const StampedPose& p : *slam) picture.slam.push_back(p.pose);
  }
  return LoadOverlayWorld(args.world, picture);
}

drawing::Bounds PictureBounds(const Picture& picture) {
  drawing::Bounds bounds = picture.world ? sim::WorldBounds(*picture.world) : drawing::Bounds();
  if (picture.map) {
    const Eigen::Vector2d origin = picture.map->origin.head<2>();
    bounds.Add(origin);
    bounds.Add(origin +
               picture.map->resolution * Eigen::Vector2d(picture.map->width, picture.map->height));
  }
  for (const auto* poses : {&picture.truth, &picture.odometry, &picture.slam}) {
    for (const Pose2& pose : *poses) bounds.Add(pose.translation());
  }
  for (const Eigen::Vector2d& p : picture.scan_points) bounds.Add(p);
  return bounds;
}

Status Draw(const Picture& picture, const RenderArgs& args) {
  drawing::DrawingOptions options;
  options.pixels_per_meter = args.scale;
  Result<drawing::TopDownCanvas> canvas =
      drawing::TopDownCanvas::Create(PictureBounds(picture), options);
  if (!canvas.ok()) return canvas.status().WithContext(args.input);
  if (picture.map) {
    drawing::DrawGreyImage(MapToGrey(*picture.map), picture.map->origin.head<2>(),
                           picture.map->resolution, *canvas);
  }
  if (picture.world) sim::DrawWorld(*picture.world, *canvas);
  if (picture.semantic) DrawSemanticMap(*picture.semantic, *canvas);
  drawing::DrawPoints(picture.scan_points, kScanColor, "laser returns", *canvas);
  drawing::DrawTrajectory(picture.odometry, kOdometryColor, "odometry", *canvas);
  drawing::DrawTrajectory(picture.truth, kTruthColor, "truth", *canvas);
  drawing::DrawTrajectory(picture.slam, kSlamColor, "SLAM trajectory", *canvas);
  return drawing::WritePng(canvas->Compose(), args.out);
}

Status RunRender(const RenderArgs& args) {
  const fs::path input(args.input);
  Picture picture;
  if (!fs::exists(input)) return Status::Error(args.input + ": no such file or directory");
  if (!fs::is_directory(input)) {
    SEMCHAIN_RETURN_IF_ERROR(LoadOverlayWorld(args.input, picture));
  } else if (fs::exists(input / "data.yaml")) {
    SEMCHAIN_RETURN_IF_ERROR(DrawDatasetGrid(input, args.split, args.frames, 4, args.out));
    std::printf("wrote %s\n", args.out.c_str());
    return Status::Ok();
  } else if (fs::exists(input / "log.clf") || fs::exists(input / "log.clf.gz")) {
    SEMCHAIN_RETURN_IF_ERROR(ReadRun(input, args, picture));
  } else if (fs::exists(input / "map.yaml")) {
    SEMCHAIN_RETURN_IF_ERROR(ReadMapDirectory(input, args, picture));
  } else {
    return Status::Error(args.input +
                         ": neither a run directory (log.clf), a map directory (map.yaml) nor a "
                         "data set (data.yaml)");
  }
  SEMCHAIN_RETURN_IF_ERROR(Draw(picture, args));
  std::printf("wrote %s\n", args.out.c_str());
  return Status::Ok();
}

}  // namespace

void AddRenderCommand(CLI::App& app, int& exit_code) {
  CLI::App* command = app.add_subcommand(
      "render",
      "Draw a world file, a run directory (trajectories, laser returns, its world) or a map "
      "directory (map, SLAM trajectory, semantic objects and chains) top-down as a PNG, or a "
      "grid of a detector data set's frames with their label boxes (semchain dataset)");
  auto args = std::make_shared<RenderArgs>();
  command->add_option("input", args->input, "World YAML, RUN directory or MAP directory")
      ->required();
  command->add_option("--out", args->out, "PNG file to write")->required();
  command->add_option("--scale", args->scale, "Pixels per metre")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command
      ->add_option("--world", args->world,
                   "World YAML drawn under a run or over a map (a run's world.yaml by default)")
      ->transform(ShippedFile());
  command->add_option("--max-scans", args->max_scans, "Laser scans of a run to draw (0: none)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  command->add_option("--split", args->split, "A data set's split to draw (train, val, test)")
      ->capture_default_str();
  command->add_option("--frames", args->frames, "Frames of a data set to draw (4 to a row)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->callback([args, &exit_code] {
    const Status status = RunRender(*args);
    exit_code = status.ok() ? 0 : ReportError(status);
  });
}

}  // namespace semchain::app
