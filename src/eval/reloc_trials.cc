#include "eval/reloc_trials.h"

#include <cmath>
#include <cstdio>
#include <random>

#include "core/angles.h"
#include "core/rng.h"
#include "io/camera_io.h"
#include "io/carmen.h"
#include "io/detections_io.h"
#include "io/rgbd_frame_io.h"
#include "mapping/slam_pipeline.h"
#include "sim/scene.h"
#include "sim/simulator.h"

namespace semchain::eval {
namespace fs = std::filesystem;
namespace {

// Random streams of the benchmark (MakeRng(seed, stream)).
constexpr std::uint64_t kTrialPoseStream = 31;

// The run's detections: options.detect's, or the simulator's RUN/detections.jsonl.
Result<std::vector<FrameDetections>> RunDetections(const RelocBenchmarkOptions& options,
                                                   const fs::path& run) {
  if (options.detect) return options.detect(run);
  return ReadDetectionsJsonl(run / "detections.jsonl");
}

}  // namespace

// The trial region must lie inside the walls' extent (the map can cover nothing else).
Status CheckTrialRegionInWorld(const sim::World& world, const std::string& source) {
  if (world.trial_region.size() < 3) {
    return Status::Error(source + ": trial_region: the live world needs a trial region");
  }
  Eigen::Vector2d low(1e300, 1e300), high(-1e300, -1e300);
  for (const auto& wall : world.walls) {
    for (const Eigen::Vector2d& p : wall) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
  }
  for (const Eigen::Vector2d& p : world.trial_region) {
    if ((p.array() < low.array()).any() || (p.array() > high.array()).any()) {
      char text[160];
      std::snprintf(text, sizeof(text),
                    ": trial_region: point (%.2f, %.2f) lies outside the map (walls span "
                    "(%.2f, %.2f) to (%.2f, %.2f))",
                    p.x(), p.y(), low.x(), low.y(), high.x(), high.y());
      return Status::Error(source + text);
    }
  }
  return Status::Ok();
}

// Uniform poses in the trial region, in free space at least 'clearance' from every surface.
Result<std::vector<Pose2>> RelocTrialStarts(const sim::World& world, int count, double clearance,
                                            std::uint64_t seed, const std::string& source) {
  // CheckTrialRegionInWorld has made sure there is a region.
  const sim::Scene scene(world);
  Eigen::Vector2d low = world.trial_region.front();
  Eigen::Vector2d high = low;
  for (const Eigen::Vector2d& p : world.trial_region) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  Rng rng = MakeRng(seed, kTrialPoseStream);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Pose2> poses;
  constexpr int kTriesPerPose = 10000;
  for (int tries = 0; static_cast<int>(poses.size()) < count; ++tries) {
    if (tries > kTriesPerPose * count) {
      return Status::Error(source + ": trial_region: no free pose " + std::to_string(clearance) +
                           " m from every surface found in it");
    }
    // y before x, one statement each: a constructor's arguments are evaluated in an unspecified
    // order (GCC last to first, as the published trials were drawn; clang first to last).
    const double y_draw = unit(rng);
    const double x_draw = unit(rng);
    const Eigen::Vector2d p = low + (high - low).cwiseProduct(Eigen::Vector2d(x_draw, y_draw));
    if (!sim::PolygonContains(world.trial_region, p) || scene.IsOccupied(p, clearance)) continue;
    poses.emplace_back(p.x(), p.y(), NormalizeAngle(2.0 * M_PI * unit(rng)));
  }
  return poses;
}

Result<RelocTrialRun> SimulateRelocTrial(const sim::World& world, const Pose2& start,
                                         std::uint64_t seed, const RelocBenchmarkOptions& options,
                                         const fs::path& run) {
  sim::SimulationOptions simulation;
  simulation.seed = seed;
  simulation.start = start;
  simulation.show_progress = false;
  simulation.route.kind = sim::RouteSpec::Kind::kTrial;
  simulation.trial.rotation_radians = 2.0 * M_PI * options.trial_turns;
  simulation.trial.forward_distance_meters = options.trial_forward;
  simulation.trial.face_most_open = options.trial_face_open;
  simulation.trial.rotation_after_radians = 2.0 * M_PI * options.trial_turns_after;
  SEMCHAIN_RETURN_IF_ERROR(sim::Simulate(world, simulation, run));
  return LoadRelocTrial(seed, options, run);
}

Result<RelocTrialRun> LoadRelocTrial(std::uint64_t seed, const RelocBenchmarkOptions& options,
                                     const fs::path& run) {
  RelocTrialRun data;
  Result<carmen::Log> log = carmen::ReadLog(run / "log.clf");
  if (!log.ok()) return log.status();
  Result<std::vector<StampedScan>> scans = mapping::ScansFromLog(*log, (run / "log.clf").string());
  if (!scans.ok()) return scans.status();
  data.inputs.scans = std::move(*scans);
  Result<std::vector<FrameDetections>> frames = RunDetections(options, run);
  if (!frames.ok()) return frames.status();
  for (const FrameDetections& frame : *frames) {
    data.inputs.frames.push_back({frame.stamp, frame.detections, ColorImagePath(run, frame.frame)});
  }
  Result<CameraInfo> camera = ReadCameraYaml(run / "camera.yaml");
  if (!camera.ok()) return camera.status();
  data.inputs.camera = camera->camera;
  data.inputs.seed = seed;
  Result<std::vector<StampedPose>> truth = ReadTrajectory(run / "truth.txt");
  if (!truth.ok()) return truth.status();
  data.truth = std::move(*truth);
  if (data.truth.size() != data.inputs.scans.size()) {
    return Status::Error(run.string() + ": truth.txt and log.clf disagree on the scan count");
  }
  return data;
}

}  // namespace semchain::eval
