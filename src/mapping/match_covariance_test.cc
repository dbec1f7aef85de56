#include "mapping/match_covariance.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "core/angles.h"
#include "mapping/testing/synthetic_map.h"

namespace semchain::mapping {
namespace {

// Returns of a scan simulated in 'world' at 'pose', in the robot frame.
std::vector<Eigen::Vector2d> ScanPoints(const std::vector<testing::Segment>& world,
                                        const Pose2& pose, double max_range) {
  const LaserScan scan = testing::SimulateScan(world, pose, 361, 1.5 * kPi, max_range);
  std::vector<Eigen::Vector2d> points;
  for (std::size_t i = 0; i < scan.size(); i += 2) {
    if (!scan.IsReturn(i)) continue;
    const double a = scan.BeamAngle(i);
    points.emplace_back(scan.ranges[i] * std::cos(a), scan.ranges[i] * std::sin(a));
  }
  return points;
}

// In a room with inner walls every direction is pinned: the match's covariance is a few
// centimetres and under a degree.
TEST(MatchCovarianceTest, AMatchInARoomIsCertainEveryWay) {
  const MatchGrid grid = MakeMatchGrid(testing::RoomMap());
  const Pose2 pose(-1.1, 0.4, 0.3);
  MatchCovarianceOptions options;
  options.window_meters = 1.0;  // a room's width: the default ±8 m costs 60 times the poses
  const Eigen::Matrix3d covariance =
      MatchCovariance(grid, ScanPoints(testing::RoomWorld(), pose, 12.0), pose, options);
  EXPECT_LT(std::sqrt(covariance(0, 0)), 0.06);
  EXPECT_LT(std::sqrt(covariance(1, 1)), 0.06);
  EXPECT_LT(std::sqrt(covariance(2, 2)), DegToRad(1.0));
}

// Down a corridor 2 m wide (running at 30°, its ends out of the laser's 5 m reach) the match is
// certain across the corridor and not along it: the covariance's long axis is the corridor's,
// as wide as the window lets it be (a uniform spread over ±2 m has σ = 2/√3 m).
TEST(MatchCovarianceTest, AMatchDownACorridorIsUncertainAlongIt) {
  const double heading = DegToRad(30.0);
  const Eigen::Vector2d along(std::cos(heading), std::sin(heading));
  const Eigen::Vector2d across(-along.y(), along.x());
  const std::vector<testing::Segment> corridor = {{-20.0 * along + across, 20.0 * along + across},
                                                  {-20.0 * along - across, 20.0 * along - across}};
  const MatchGrid grid = MakeMatchGrid(testing::RasterizeWorld(
      corridor, Eigen::Vector2d(-20.0, -13.0), Eigen::Vector2d(20.0, 13.0)));
  const Pose2 pose(0.3, -0.2, heading + 0.2);
  MatchCovarianceOptions options;
  options.window_meters = 2.0;
  const Eigen::Matrix3d covariance =
      MatchCovariance(grid, ScanPoints(corridor, pose, 5.0), pose, options);
  const Eigen::Matrix2d planar = covariance.topLeftCorner<2, 2>();
  EXPECT_GT(std::sqrt(along.dot(planar * along)), 0.8);
  EXPECT_LT(std::sqrt(across.dot(planar * across)), 0.1);
  EXPECT_LT(std::sqrt(covariance(2, 2)), DegToRad(2.0));
}

TEST(MatchCovarianceTest, OptionsAreChecked) {
  std::string error;
  EXPECT_TRUE(MatchCovarianceOptions{}.Validate(&error));
  MatchCovarianceOptions zero_step;
  zero_step.linear_step_meters = 0.0;
  EXPECT_FALSE(zero_step.Validate(&error));
  MatchCovarianceOptions no_drop;
  no_drop.score_drop = 0.0;
  EXPECT_FALSE(no_drop.Validate(&error));
}

}  // namespace
}  // namespace semchain::mapping
