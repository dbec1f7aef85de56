#include "sim/lidar.h"

#include <algorithm>
#include <random>

#include "core/angles.h"

namespace semchain::sim {

Pose2 RobotFromLidar(const LidarSpec& spec) { return Pose2(spec.forward_offset, 0.0, 0.0); }

LaserScan MakeEmptyScan(const LidarSpec& spec) {
  LaserScan scan;
  scan.max_range = spec.max_range;
  const double fov = DegToRad(spec.fov_deg);
  if (spec.fov_deg >= 360.0) {
    scan.angle_min = -kPi;
    scan.angle_increment = 2.0 * kPi / spec.beams;
  } else {
    scan.angle_min = -0.5 * fov;
    scan.angle_increment = spec.beams > 1 ? fov / (spec.beams - 1) : 0.0;
  }
  return scan;
}

LaserScan SimulateScan(const Scene& scene, const LidarSpec& spec, const Pose2& robot_pose,
                       double timestamp, Rng& rng) {
  LaserScan scan = MakeEmptyScan(spec);
  scan.timestamp = timestamp;
  scan.ranges.resize(spec.beams);
  const Pose2 lidar = robot_pose * RobotFromLidar(spec);
  std::normal_distribution<double> noise(0.0, spec.noise_std);
  for (int i = 0; i < spec.beams; ++i) {
    const double angle = lidar.theta + scan.BeamAngle(i);
    const auto hit = scene.CastAtHeight(lidar.translation(), angle, spec.max_range, spec.height);
    double range = spec.max_range;
    if (hit) {
      // One draw per returning beam: which beams return depends only on the geometry, so the
      // noise sequence is reproducible for a given trajectory and seed.
      const double noisy = hit->distance + (spec.noise_std > 0.0 ? noise(rng) : 0.0);
      range = std::clamp(noisy, 0.0, spec.max_range);
    }
    scan.ranges[i] = range;
  }
  return scan;
}

}  // namespace semchain::sim
