#include "mapping/loop_closure.h"

#include <gtest/gtest.h>

#include <random>

#include "core/angles.h"
#include "core/rng.h"
#include "mapping/testing/synthetic_world.h"

namespace semchain::mapping {
namespace {

using testing::Segment;

// A corridor 2 m wide around a 40 m × 20 m block, with door niches and boxes scattered along
// both walls so that places differ.
std::vector<Segment> CorridorLoopWorld() {
  std::vector<Segment> world;
  auto box = [&world](double x0, double y0, double x1, double y1) {
    world.push_back({{x0, y0}, {x1, y0}});
    world.push_back({{x1, y0}, {x1, y1}});
    world.push_back({{x1, y1}, {x0, y1}});
    world.push_back({{x0, y1}, {x0, y0}});
  };
  box(-2.0, -2.0, 42.0, 22.0);  // outer wall
  box(0.0, 0.0, 40.0, 20.0);    // the block
  Rng rng = MakeRng(11);
  std::uniform_real_distribution<double> along(0.0, 1.0);
  std::uniform_real_distribution<double> size(0.2, 0.5);
  for (int k = 0; k < 60; ++k) {
    // A box against one of the eight walls.
    const int wall = k % 8;
    const double t = along(rng);
    const double s = size(rng);
    const double x = 1.0 + 38.0 * t, y = 1.0 + 18.0 * t;
    switch (wall) {
      case 0:
        box(x, -2.0, x + s, -2.0 + s);
        break;
      case 1:
        box(x, 0.0 - s, x + s, 0.0);
        break;
      case 2:
        box(x, 22.0 - s, x + s, 22.0);
        break;
      case 3:
        box(x, 20.0, x + s, 20.0 + s);
        break;
      case 4:
        box(-2.0, y, -2.0 + s, y + s);
        break;
      case 5:
        box(0.0 - s, y, 0.0, y + s);
        break;
      case 6:
        box(42.0 - s, y, 42.0, y + s);
        break;
      default:
        box(40.0, y, 40.0 + s, y + s);
        break;
    }
  }
  return world;
}

struct LoopRun {
  std::vector<PreparedScan> scans;
  std::vector<Pose2> truth;
  std::vector<Pose2> drifted;  // what a filter with a slow heading drift would give
};

// Two laps anticlockwise along the corridor's centre line, a node every 0.5 m.
LoopRun DriveTwoLaps(double drift_radians_per_meter) {
  const std::vector<Segment> world = CorridorLoopWorld();
  const std::vector<Eigen::Vector2d> corners = {{-1, -1}, {41, -1}, {41, 21}, {-1, 21}};
  LoopRun run;
  Rng rng = MakeRng(2);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (int lap = 0; lap < 2; ++lap) {
    for (int side = 0; side < 4; ++side) {
      const Eigen::Vector2d a = corners[static_cast<std::size_t>(side)];
      const Eigen::Vector2d b = corners[static_cast<std::size_t>((side + 1) % 4)];
      const int steps = static_cast<int>((b - a).norm() / 0.5);
      const double heading = std::atan2(b.y() - a.y(), b.x() - a.x());
      for (int k = 0; k < steps; ++k) {
        const Eigen::Vector2d at = a + (b - a) * (static_cast<double>(k) / steps);
        run.truth.emplace_back(at.x(), at.y(), heading);
      }
    }
  }
  run.drifted.push_back(run.truth.front());
  for (std::size_t i = 0; i < run.truth.size(); ++i) {
    LaserScan scan = testing::SimulateScan(world, run.truth[i], 271, 1.5 * kPi, 30.0);
    for (double& r : scan.ranges) r += noise(rng);
    run.scans.push_back(PrepareScan(scan, Pose2(), {}));
    if (i == 0) continue;
    Pose2 step = run.truth[i - 1].Between(run.truth[i]);
    step.theta += drift_radians_per_meter * step.translation().norm();
    run.drifted.push_back(run.drifted.back() * step);
  }
  return run;
}

std::vector<const PreparedScan*> Pointers(const std::vector<PreparedScan>& scans) {
  std::vector<const PreparedScan*> pointers;
  for (const PreparedScan& scan : scans) pointers.push_back(&scan);
  return pointers;
}

TEST(LoopClosureTest, ClosingTheLoopsRemovesTheDrift) {
  const LoopRun run = DriveTwoLaps(DegToRad(0.05));
  const double before = testing::MaxPositionError(run.drifted, run.truth);
  ASSERT_GT(before, 1.5);
  const LoopClosureResult result = CloseLoops(Pointers(run.scans), run.drifted, {});
  const LoopClosureStatistics& stats = result.statistics;
  EXPECT_GE(stats.accepted, 5);
  EXPECT_GT(stats.searches, stats.accepted);
  for (const double residual : stats.residuals) EXPECT_LT(residual, 5.0);
  EXPECT_LT(testing::MaxPositionError(result.poses, run.truth), 0.3) << "before: " << before;
}

// Submaps freed from the cache are rebuilt identically: keeping one built or all of them gives
// the same closures and the same poses.
TEST(LoopClosureTest, TheBuiltSubmapCacheDoesNotChangeTheResult) {
  const LoopRun run = DriveTwoLaps(DegToRad(0.05));
  LoopClosureOptions one, all;
  one.max_built_submaps = 1;
  all.max_built_submaps = 1000;
  const LoopClosureResult a = CloseLoops(Pointers(run.scans), run.drifted, one);
  const LoopClosureResult b = CloseLoops(Pointers(run.scans), run.drifted, all);
  ASSERT_GT(a.statistics.submaps, 2);
  EXPECT_EQ(a.statistics.found, b.statistics.found);
  EXPECT_EQ(a.statistics.accepted, b.statistics.accepted);
  EXPECT_EQ(a.statistics.residuals, b.statistics.residuals);
  ASSERT_EQ(a.poses.size(), b.poses.size());
  for (std::size_t i = 0; i < a.poses.size(); ++i) {
    EXPECT_EQ(a.poses[i].x, b.poses[i].x) << i;
    EXPECT_EQ(a.poses[i].y, b.poses[i].y) << i;
    EXPECT_EQ(a.poses[i].theta, b.poses[i].theta) << i;
  }
}

TEST(LoopClosureTest, NoDriftNoHarm) {
  const LoopRun run = DriveTwoLaps(0.0);
  const LoopClosureResult result = CloseLoops(Pointers(run.scans), run.drifted, {});
  EXPECT_GE(result.statistics.accepted, 1);
  EXPECT_LT(testing::MaxPositionError(result.poses, run.truth), 0.1);
}

}  // namespace
}  // namespace semchain::mapping
