#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "core/pose2.h"
#include "core/status.h"
#include "sim/route_follower.h"
#include "sim/world.h"

// The simulation run (DESIGN.md §3.1, §4 `semchain simulate`): drives the robot along a route
// and writes a run directory:
//   log.clf           CARMEN log: PARAM, then per scan ODOM, TRUEPOS and ROBOTLASER1 lines
//   truth.txt         "timestamp x y theta": the true pose at every scan (same timestamps)
//   camera.yaml       intrinsics, depth encoding and robot_from_camera of the RGB-D camera
//   frames/NNNNNN.png RGB frames, NNNNNN_depth.png 16-bit depth in millimetres
//   detections.jsonl  one line per frame (DESIGN.md §5.5), frame "frames/NNNNNN"
//   run.yaml          what was simulated: world, seed, route, start, counts, rates
namespace semchain::sim {

struct SimulationOptions {
  std::uint64_t seed = 0;  // every noise source draws from its own stream of this seed
  RouteSpec route;         // the world's mapping route by default
  // Where the robot starts (world frame); the world's robot.start when not set. Trials of
  // `bench reloc` set it to their random poses.
  std::optional<Pose2> start;
  TrialOptions trial;
  bool write_frames = true;   // false: no frames/ and no detections.jsonl (`--no-frames`)
  bool show_progress = true;  // a progress bar on stderr when it is a terminal
  // The world file's text; when set it is copied to RUN/world.yaml so that the run carries
  // its world (render draws it, later stages read the objects' truth from it).
  std::string world_yaml;
};

// The independent random streams of a run (MakeRng(seed, stream)).
enum class SimStream : std::uint64_t {
  kLidar = 1,
  kOdometry = 2,
  kDetections = 3,
  kDepthNoise = 4,
};

// Simulates 'world' as 'options' says and writes the run directory 'run_dir'. The same world
// and options give a byte-identical directory. The directory is assembled beside 'run_dir'
// and moved into place at the end, so a failed run leaves nothing behind. 'run_dir' may be
// absent, an empty directory or an earlier run (it has run.yaml), which is replaced; anything
// else (a file, a directory of other things) is refused.
Status Simulate(const World& world, const SimulationOptions& options,
                const std::filesystem::path& run_dir);

}  // namespace semchain::sim
