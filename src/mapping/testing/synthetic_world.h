#pragma once

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/angles.h"
#include "core/pose2.h"
#include "core/rng.h"
#include "sensors/laser_scan.h"

// Test helper: an analytic world of line segments and a laser that ray-casts it exactly.
namespace semchain::mapping::testing {

struct Segment {
  Eigen::Vector2d a, b;
};

// A 10 m × 8 m room with a few inner walls and a box, so that every degree of freedom of a
// scan match is constrained.
inline std::vector<Segment> RoomWorld() {
  auto box = [](double x0, double y0, double x1, double y1) {
    return std::vector<Segment>{
        {{x0, y0}, {x1, y0}}, {{x1, y0}, {x1, y1}}, {{x1, y1}, {x0, y1}}, {{x0, y1}, {x0, y0}}};
  };
  std::vector<Segment> world = box(-5, -4, 5, 4);
  for (const Segment& s : box(1.0, 1.0, 1.6, 1.5)) world.push_back(s);
  for (const Segment& s : box(-3.0, -2.5, -2.2, -2.0)) world.push_back(s);
  world.push_back({{-1.0, 4.0}, {-1.0, 3.6}});
  world.push_back({{3.0, -4.0}, {3.5, -3.6}});
  return world;
}

// Clutter without long walls (a lab full of furniture): 'posts' posts of 0.2 m scattered over
// 16 m × 16 m, none within 1 m of the origin. A rotation of a scan moves every endpoint off its
// post, so the matching score has no slope towards the right heading beyond a few degrees.
inline std::vector<Segment> ClutteredWorld(int posts = 60, std::uint64_t seed = 3) {
  std::vector<Segment> world;
  Rng rng = MakeRng(seed);
  std::uniform_real_distribution<double> coordinate(-8.0, 8.0);
  while (world.size() < 4 * static_cast<std::size_t>(posts)) {
    const double x = coordinate(rng), y = coordinate(rng);
    if (std::hypot(x, y) < 1.0) continue;
    const double h = 0.1;
    world.push_back({{x - h, y - h}, {x + h, y - h}});
    world.push_back({{x + h, y - h}, {x + h, y + h}});
    world.push_back({{x + h, y + h}, {x - h, y + h}});
    world.push_back({{x - h, y + h}, {x - h, y - h}});
  }
  return world;
}

// Distance from 'origin' along unit 'direction' to the nearest segment, or +inf.
inline double CastRay(const std::vector<Segment>& world, const Eigen::Vector2d& origin,
                      const Eigen::Vector2d& direction) {
  double best = std::numeric_limits<double>::infinity();
  for (const Segment& s : world) {
    const Eigen::Vector2d e = s.b - s.a;
    const double denominator = direction.x() * e.y() - direction.y() * e.x();
    if (std::abs(denominator) < 1e-12) continue;
    const Eigen::Vector2d w = s.a - origin;
    const double t = (w.x() * e.y() - w.y() * e.x()) / denominator;
    const double u = (w.x() * direction.y() - w.y() * direction.x()) / denominator;
    if (t > 0.0 && u >= 0.0 && u <= 1.0) best = std::min(best, t);
  }
  return best;
}

// The largest distance between corresponding positions of 'poses' and 'truth'.
inline double MaxPositionError(const std::vector<Pose2>& poses, const std::vector<Pose2>& truth) {
  double worst = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    worst = std::max(worst, (poses[i].translation() - truth[i].translation()).norm());
  }
  return worst;
}

// A 'beams'-beam scan over 'fov' centred ahead, taken by a laser at 'pose'.
inline LaserScan SimulateScan(const std::vector<Segment>& world, const Pose2& pose, int beams = 361,
                              double fov = kPi, double max_range = 30.0) {
  LaserScan scan;
  scan.angle_min = -0.5 * fov;
  scan.angle_increment = fov / (beams - 1);
  scan.max_range = max_range;
  for (int i = 0; i < beams; ++i) {
    const double angle = pose.theta + scan.BeamAngle(static_cast<std::size_t>(i));
    const double range =
        CastRay(world, pose.translation(), Eigen::Vector2d(std::cos(angle), std::sin(angle)));
    scan.ranges.push_back(std::min(range, max_range));
  }
  return scan;
}

// A robot driving a rectangle in RoomWorld: every 'step' metres a scan (range noise
// 'range_noise' m) with odometry that over-reads distance by 3 % and turns 2 % too little,
// plus seeded jitter, starting at the true first pose.
struct SimulatedRun {
  std::vector<StampedScan> scans;
  std::vector<Pose2> truth;
};

inline SimulatedRun SimulateRoomRun(double step = 0.1, double range_noise = 0.01,
                                    std::uint64_t seed = 1) {
  const std::vector<Segment> world = RoomWorld();
  const std::vector<Eigen::Vector2d> corners = {{-3.8, -3.2}, {3.8, -3.2}, {3.8, 0.3},
                                                {-0.2, 0.3},  {-0.2, 3.2}, {-3.8, 3.2},
                                                {-3.8, -3.2}, {0.0, -3.2}};
  Rng rng = MakeRng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  SimulatedRun run;
  Pose2 odometry;
  for (std::size_t c = 0; c + 1 < corners.size(); ++c) {
    const Eigen::Vector2d delta = corners[c + 1] - corners[c];
    const double heading = std::atan2(delta.y(), delta.x());
    const int steps = static_cast<int>(delta.norm() / step);
    for (int i = 0; i < steps; ++i) {
      const Eigen::Vector2d at = corners[c] + delta * (static_cast<double>(i) / steps);
      const Pose2 pose(at.x(), at.y(), heading);
      if (run.truth.empty()) {
        odometry = pose;
      } else {
        const Pose2 motion = run.truth.back().Between(pose);
        // θ before x, one statement each: argument order is unspecified (GCC's, last to
        // first, made the fixtures that use this run).
        const double theta_noise = 0.002 * noise(rng);
        const double x_noise = 0.002 * noise(rng);
        odometry = odometry *
                   Pose2(motion.x * 1.03 + x_noise, motion.y, motion.theta * 0.98 + theta_noise);
      }
      LaserScan scan = SimulateScan(world, pose);
      for (double& r : scan.ranges) r += range_noise * noise(rng);
      scan.timestamp = static_cast<double>(run.truth.size()) * 0.2;
      run.scans.push_back({scan, odometry, odometry});
      run.truth.push_back(pose);
    }
  }
  return run;
}

}  // namespace semchain::mapping::testing
