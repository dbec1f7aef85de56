#include "sim/simulator.h"

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "core/angles.h"
#include "core/atomic_file.h"
#include "core/progress_bar.h"
#include "core/rng.h"
#include "io/camera_io.h"
#include "io/carmen.h"
#include "io/trajectory_io.h"
#include "sim/frame_recorder.h"
#include "sim/lidar.h"
#include "sim/odometry_model.h"
#include "sim/run_directory.h"
#include "sim/scene.h"

namespace semchain::sim {
namespace fs = std::filesystem;
namespace {

constexpr char kHost[] = "semchain";

Rng StreamRng(const SimulationOptions& options, SimStream stream) {
  return MakeRng(options.seed, static_cast<std::uint64_t>(stream));
}

std::string RouteName(const RouteSpec& route) {
  switch (route.kind) {
    case RouteSpec::Kind::kMapping:
      return "mapping";
    case RouteSpec::Kind::kTrial:
      return "trial";
    case RouteSpec::Kind::kWaypoints:
      return "waypoints";
  }
  return "";
}

std::string Number(double value) {
  char text[40];
  std::snprintf(text, sizeof(text), "%.9g", value);
  return text;
}

// The log's header: comments for people, PARAM lines for CARMEN tools. ROBOTLASER1 lines carry
// start angle, fov and resolution themselves, and readers that honour them (ours, CARMEN's)
// need nothing else. GMapping's reader (log/carmenconfiguration.cpp) parses these logs but
// ignores those fields: it takes the beam count from the first laser line, the resolution from
// laser_front_laser_resolution (except for 180/181/360/361/540/541 beams, which it hard-codes
// as 1° or 0.5° scans) and lays the beams out symmetrically about the heading, skipping the
// centre beam of an even count. Our full-circle layout starts at -π, so GMapping's own tools
// misplace its beams (wholly for 360 beams, by half a beam for an odd count).
void AddHeader(const World& world, const SimulationOptions& options, carmen::Log* log) {
  const LidarSpec& lidar = world.robot.lidar;
  const LaserScan layout = MakeEmptyScan(lidar);
  const auto comment = [log](const std::string& text) {
    log->records.push_back(carmen::Other{"# " + text});
  };
  comment("CARMEN Logfile written by semchain simulate");
  comment("world " + world.name + ", seed " + std::to_string(options.seed) + ", route " +
          RouteName(options.route));
  comment("per scan: ODOM (odometry with noise), TRUEPOS (truth), ROBOTLASER1 (the scan)");
  const auto param = [log](const std::string& name, const std::string& value) {
    log->records.push_back(carmen::Param{name, value, ""});
  };
  param("robot_frontlaser_offset", Number(lidar.forward_offset));
  param("laser_front_laser_fov", Number(lidar.fov_deg));
  param("laser_front_laser_resolution", Number(RadToDeg(layout.angle_increment)));
  param("robot_front_laser_max", Number(lidar.max_range));
}

void AddScanRecords(const TrajectorySample& sample, const Pose2& odometry, const LaserScan& scan,
                    const LidarSpec& lidar, carmen::Log* log) {
  const carmen::Stamp stamp{sample.time, kHost, sample.time};
  log->records.push_back(
      carmen::Odometry{odometry, sample.velocity.linear, sample.velocity.angular, 0.0, stamp});
  log->records.push_back(carmen::TruePose{sample.pose, odometry, stamp});
  carmen::Laser laser;
  laser.kind = carmen::Laser::Kind::kRobotLaser1;
  laser.scan.scan = scan;
  laser.scan.odometry = odometry;
  laser.scan.laser_pose = odometry * RobotFromLidar(lidar);
  laser.accuracy = lidar.noise_std;
  laser.tv = sample.velocity.linear;
  laser.rv = sample.velocity.angular;
  laser.stamp = stamp;
  log->records.push_back(laser);
}

std::string FormatRunYaml(const World& world, const SimulationOptions& options, const Pose2& start,
                          const std::vector<TrajectorySample>& samples, int frames) {
  std::string text = "# What `semchain simulate` did to make this run directory.\n";
  text += "world: " + world.name + "\n";
  text += "seed: " + std::to_string(options.seed) + "\n";
  text += "route: " + RouteName(options.route) + "\n";
  text +=
      "start: [" + Number(start.x) + ", " + Number(start.y) + ", " + Number(start.theta) + "]\n";
  text += "scans: " + std::to_string(samples.size()) + "\n";
  text += "scan_rate_hz: " + Number(world.robot.scan_rate_hz) + "\n";
  text += "duration_s: " + Number(samples.back().time) + "\n";
  text += "frames: " + std::to_string(frames) + "\n";
  text += "frame_rate_hz: " + Number(options.write_frames ? world.robot.frame_rate_hz : 0.0) + "\n";
  return text;
}

// Simulates the sensors along 'samples' and writes every file into 'dir'.
Status WriteRun(const Scene& scene, const std::vector<TrajectorySample>& samples,
                const SimulationOptions& options, const fs::path& dir) {
  const World& world = scene.world();
  Rng lidar_rng = StreamRng(options, SimStream::kLidar);
  Rng odometry_rng = StreamRng(options, SimStream::kOdometry);
  OdometrySimulator odometry(world.robot.odometry_noise, samples.front().pose,
                             world.robot.odometry_scale_error);
  std::optional<FrameRecorder> frames;
  if (options.write_frames) {
    frames.emplace(scene, options.seed, dir);
    SEMCHAIN_RETURN_IF_ERROR(frames->Open());
  }
  carmen::Log log;
  AddHeader(world, options, &log);
  std::vector<StampedPose> truth;
  std::optional<ProgressBar> progress;
  if (options.show_progress) progress.emplace("simulate", samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const TrajectorySample& sample = samples[i];
    const Pose2 odom = i == 0 ? odometry.pose() : odometry.Step(sample.pose, odometry_rng);
    const LaserScan scan =
        SimulateScan(scene, world.robot.lidar, sample.pose, sample.time, lidar_rng);
    AddScanRecords(sample, odom, scan, world.robot.lidar, &log);
    truth.push_back({sample.time, sample.pose});
    if (frames) SEMCHAIN_RETURN_IF_ERROR(frames->MaybeCapture(sample));
    if (progress) progress->Update(i + 1);
  }
  if (progress) progress->Finish();
  SEMCHAIN_RETURN_IF_ERROR(carmen::WriteLog(dir / "log.clf", log));
  SEMCHAIN_RETURN_IF_ERROR(WriteTrajectory(dir / "truth.txt", truth));
  if (frames) SEMCHAIN_RETURN_IF_ERROR(frames->Close());
  const int frame_count = frames ? frames->count() : 0;
  if (!options.world_yaml.empty()) {
    SEMCHAIN_RETURN_IF_ERROR(WriteFileAtomically(dir / "world.yaml", options.world_yaml));
  }
  CameraInfo camera_info;
  camera_info.camera = MakeMountedCamera(world.robot.camera);
  camera_info.frame_rate_hz = world.robot.frame_rate_hz;
  SEMCHAIN_RETURN_IF_ERROR(WriteCameraYaml(dir / "camera.yaml", camera_info));
  return WriteFileAtomically(
      dir / "run.yaml", FormatRunYaml(world, options, samples.front().pose, samples, frame_count));
}

}  // namespace

Status Simulate(const World& world, const SimulationOptions& options, const fs::path& run_dir) {
  fs::path dir = run_dir.lexically_normal();
  if (!dir.has_filename()) dir = dir.parent_path();
  if (dir.empty() || dir == ".") return Status::Error("the output directory must be named");
  Result<fs::path> staging = BeginRunDirectory(dir);
  if (!staging.ok()) return staging.status();
  const Scene scene(world);
  TrajectoryOptions trajectory_options;
  trajectory_options.sample_rate_hz = world.robot.scan_rate_hz;
  trajectory_options.trial = options.trial;
  const Pose2 start = options.start.value_or(world.robot.start);
  Result<std::vector<TrajectorySample>> samples =
      GenerateTrajectory(scene, world.robot, options.route, start, trajectory_options);
  Status status =
      samples.status().WithContext("world " + world.name + ", route " + RouteName(options.route));
  if (status.ok()) status = WriteRun(scene, *samples, options, *staging);
  if (!status.ok()) {
    AbandonRunDirectory(*staging);
    return status;
  }
  return FinishRunDirectory(*staging, dir);
}

}  // namespace semchain::sim
