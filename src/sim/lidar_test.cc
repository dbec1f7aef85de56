#include "sim/lidar.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/angles.h"

namespace semchain::sim {
namespace {

World Room() {
  World world;
  world.walls = {{{0, 0}, {10, 0}, {10, 6}, {0, 6}, {0, 0}}};
  return world;
}

Solid LowBox(double x, double y, double height) {
  Solid box;
  box.footprint.center = {x, y};
  box.footprint.width = 0.4;
  box.footprint.depth = 0.4;
  box.height = height;
  return box;
}

LidarSpec Noiseless(int beams, double fov_deg) {
  LidarSpec spec;
  spec.beams = beams;
  spec.fov_deg = fov_deg;
  spec.noise_std = 0.0;
  spec.max_range = 12.0;
  return spec;
}

TEST(LidarTest, FullCircleBeamLayout) {
  const LaserScan scan = MakeEmptyScan(Noiseless(360, 360));
  EXPECT_NEAR(scan.angle_min, -kPi, 1e-12);
  EXPECT_NEAR(scan.angle_increment, DegToRad(1.0), 1e-12);
  EXPECT_NEAR(scan.BeamAngle(180), 0.0, 1e-12);  // beam 180 looks straight ahead
  const LaserScan front = MakeEmptyScan(Noiseless(181, 180));
  EXPECT_NEAR(front.angle_min, -kPi / 2, 1e-12);
  EXPECT_NEAR(front.BeamAngle(180), kPi / 2, 1e-12);  // a partial fov spans end to end
}

TEST(LidarTest, RangesToWallsAreAnalytic) {
  const Scene scene(Room());
  Rng rng = MakeRng(1);
  const LaserScan scan = SimulateScan(scene, Noiseless(360, 360), Pose2(2.0, 3.0, 0.0), 4.5, rng);
  ASSERT_EQ(scan.size(), 360u);
  EXPECT_DOUBLE_EQ(scan.timestamp, 4.5);
  EXPECT_NEAR(scan.ranges[180], 8.0, 1e-9);  // ahead: wall x = 10
  EXPECT_NEAR(scan.ranges[270], 3.0, 1e-9);  // left: wall y = 6
  EXPECT_NEAR(scan.ranges[0], 2.0, 1e-9);    // behind: wall x = 0
  EXPECT_NEAR(scan.ranges[90], 3.0, 1e-9);   // right: wall y = 0
  // Beam at +30°: meets y = 6 at 3 / sin 30° = 6 m.
  EXPECT_NEAR(scan.ranges[210], 6.0, 1e-9);
  // The robot's heading turns the scan with it: facing +y, beam 180 sees y = 6.
  const LaserScan turned =
      SimulateScan(scene, Noiseless(360, 360), Pose2(2.0, 3.0, kPi / 2), 0.0, rng);
  EXPECT_NEAR(turned.ranges[180], 3.0, 1e-9);
}

TEST(LidarTest, ForwardOffsetMovesTheScanOrigin) {
  const Scene scene(Room());
  LidarSpec spec = Noiseless(4, 360);
  spec.forward_offset = 0.25;
  Rng rng = MakeRng(1);
  const LaserScan scan = SimulateScan(scene, spec, Pose2(2.0, 3.0, 0.0), 0.0, rng);
  EXPECT_NEAR(scan.ranges[2], 7.75, 1e-9);  // beam 2 of 4 looks ahead
  EXPECT_NEAR(scan.ranges[0], 2.25, 1e-9);
}

TEST(LidarTest, BeyondMaxRangeReadsMaxRange) {
  const Scene scene(Room());
  LidarSpec spec = Noiseless(360, 360);
  spec.max_range = 5.0;
  Rng rng = MakeRng(1);
  const LaserScan scan = SimulateScan(scene, spec, Pose2(2.0, 3.0, 0.0), 0.0, rng);
  EXPECT_DOUBLE_EQ(scan.ranges[180], 5.0);  // the wall is 8 m away
  EXPECT_FALSE(scan.IsReturn(180));
  EXPECT_TRUE(scan.IsReturn(0));
}

TEST(LidarTest, ObjectBelowTheScanPlaneIsInvisible) {
  // Seed 004 §3.1: lidar at 19 cm sees obstacle A (27 cm) but not obstacle B (13 cm).
  World world = Room();
  world.obstacles.push_back(LowBox(5.0, 3.0, 0.27));  // A, front face at x = 4.8
  world.obstacles.push_back(LowBox(2.0, 1.0, 0.13));  // B, front face at y = 1.2
  const Scene scene(world);
  LidarSpec spec = Noiseless(360, 360);
  spec.height = 0.19;
  Rng rng = MakeRng(1);
  const LaserScan scan = SimulateScan(scene, spec, Pose2(2.0, 3.0, 0.0), 0.0, rng);
  EXPECT_NEAR(scan.ranges[180], 2.8, 1e-9);  // A
  EXPECT_NEAR(scan.ranges[90], 3.0, 1e-9);   // through B to the wall y = 0
  spec.height = 0.10;                        // a lidar below 13 cm sees B
  const LaserScan low = SimulateScan(scene, spec, Pose2(2.0, 3.0, 0.0), 0.0, rng);
  EXPECT_NEAR(low.ranges[90], 1.8, 1e-9);
}

TEST(LidarTest, NoiseHasTheSpecifiedStandardDeviation) {
  const Scene scene(Room());
  LidarSpec spec = Noiseless(8, 360);
  spec.noise_std = 0.03;
  Rng rng = MakeRng(42, 1);
  const Pose2 pose(2.0, 3.0, 0.0);
  const LaserScan truth = SimulateScan(scene, Noiseless(8, 360), pose, 0.0, rng);
  double sum = 0.0, sum_sq = 0.0;
  int n = 0;
  for (int k = 0; k < 5000; ++k) {
    const LaserScan scan = SimulateScan(scene, spec, pose, 0.0, rng);
    for (std::size_t i = 0; i < scan.size(); ++i) {
      const double error = scan.ranges[i] - truth.ranges[i];
      sum += error;
      sum_sq += error * error;
      ++n;
    }
  }
  const double mean = sum / n;
  const double std = std::sqrt(sum_sq / n - mean * mean);
  // 40000 samples: the sample std is within 2% of the truth with overwhelming probability.
  EXPECT_NEAR(mean, 0.0, 0.001);
  EXPECT_NEAR(std, 0.03, 0.03 * 0.02);
}

TEST(LidarTest, SameSeedSameScan) {
  const Scene scene(Room());
  LidarSpec spec = Noiseless(90, 360);
  spec.noise_std = 0.01;
  Rng a = MakeRng(5, 1), b = MakeRng(5, 1), c = MakeRng(6, 1);
  const Pose2 pose(3.0, 2.0, 0.3);
  EXPECT_EQ(SimulateScan(scene, spec, pose, 0.0, a).ranges,
            SimulateScan(scene, spec, pose, 0.0, b).ranges);
  EXPECT_NE(SimulateScan(scene, spec, pose, 0.0, a).ranges,
            SimulateScan(scene, spec, pose, 0.0, c).ranges);
}

}  // namespace
}  // namespace semchain::sim
