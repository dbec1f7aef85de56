#include "sim/route_follower.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "core/angles.h"

namespace semchain::sim {
namespace {

using ::testing::HasSubstr;

World RouteRoom() {
  World world;
  world.walls = {{{0, 0}, {10, 0}, {10, 6}, {0, 6}, {0, 0}}};
  world.mapping_route = {{1, 1}, {8, 1}, {8, 5}, {2, 4}, {1, 1}};
  world.robot.start = Pose2(1.0, 1.0, 0.0);
  world.robot.max_speed = 0.5;
  world.robot.max_turn_rate = 1.0;
  return world;
}

double MinDistance(const std::vector<TrajectorySample>& samples, const Eigen::Vector2d& p,
                   std::size_t* index) {
  double best = 1e9;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double d = (samples[i].pose.translation() - p).norm();
    if (d < best) best = d, *index = i;
  }
  return best;
}

TEST(DiffDriveTest, ArcIntegrationIsExact) {
  // v = 1 m/s, ω = 1 rad/s: a circle of radius 1; a quarter turn ends at (1, 1) facing +y.
  const Pose2 quarter = IntegrateDiffDrive(Pose2(), {1.0, 1.0}, kPi / 2);
  EXPECT_NEAR(quarter.x, 1.0, 1e-12);
  EXPECT_NEAR(quarter.y, 1.0, 1e-12);
  EXPECT_NEAR(quarter.theta, kPi / 2, 1e-12);
  Pose2 pose(2.0, 3.0, 0.5);
  for (int i = 0; i < 100; ++i) pose = IntegrateDiffDrive(pose, {0.3, 0.6}, 2 * kPi / 0.6 / 100);
  EXPECT_NEAR(pose.x, 2.0, 1e-9);  // a full circle comes back
  EXPECT_NEAR(pose.y, 3.0, 1e-9);
  const Pose2 straight = IntegrateDiffDrive(Pose2(0, 0, kPi / 2), {0.5, 0.0}, 2.0);
  EXPECT_NEAR(straight.x, 0.0, 1e-12);
  EXPECT_NEAR(straight.y, 1.0, 1e-12);
}

TEST(RouteFollowerTest, ReachesEveryWaypointInOrderWithinLimits) {
  const World world = RouteRoom();
  const Scene scene(world);
  const auto samples = GenerateTrajectory(scene, world.robot, RouteSpec{}, world.robot.start);
  ASSERT_TRUE(samples.ok()) << samples.status().message();
  std::size_t previous = 0;
  for (const Eigen::Vector2d& waypoint : world.mapping_route) {
    std::size_t index = 0;
    // The nearest sample after the previous waypoint's; sampled at 10 Hz and 0.5 m/s, the
    // robot passes within the controller's 2 cm tolerance of each waypoint.
    std::vector<TrajectorySample> rest(samples->begin() + previous, samples->end());
    EXPECT_LT(MinDistance(rest, waypoint, &index), 0.021) << waypoint.transpose();
    previous += index;
  }
  EXPECT_LT((samples->back().pose.translation() - world.mapping_route.back()).norm(), 0.021);
  for (std::size_t i = 0; i < samples->size(); ++i) {
    const TrajectorySample& s = (*samples)[i];
    EXPECT_NEAR(s.time, 0.1 * static_cast<double>(i), 1e-9);
    EXPECT_LE(s.velocity.linear, world.robot.max_speed + 1e-12);
    EXPECT_GE(s.velocity.linear, 0.0);  // never reverses
    EXPECT_LE(std::abs(s.velocity.angular), world.robot.max_turn_rate + 1e-12);
    if (i > 0) {  // bounded speed between samples
      const double step = (s.pose.translation() - (*samples)[i - 1].pose.translation()).norm();
      EXPECT_LE(step, 0.05 + 1e-9);
    }
  }
  // The route is about 7 + 4 + 6.1 + 3.2 = 20.3 m: at 0.5 m/s plus turns, well under 60 s.
  EXPECT_LT(samples->back().time, 60.0);
}

TEST(RouteFollowerTest, TrialRotatesOnceThenDrivesAhead) {
  const World world = RouteRoom();
  const Scene scene(world);
  RouteSpec trial;
  trial.kind = RouteSpec::Kind::kTrial;
  const Pose2 start(3.0, 3.0, 0.4);
  const auto samples = GenerateTrajectory(scene, world.robot, trial, start);
  ASSERT_TRUE(samples.ok()) << samples.status().message();
  double turned = 0.0;
  bool driving = false;
  for (std::size_t i = 1; i < samples->size(); ++i) {
    turned += AngleDifference((*samples)[i].pose.theta, (*samples)[i - 1].pose.theta);
    driving = driving || (*samples)[i].velocity.linear > 0.0;
    if (!driving) {
      EXPECT_NEAR((*samples)[i].pose.x, start.x, 1e-12);  // rotating in place
      EXPECT_NEAR((*samples)[i].pose.y, start.y, 1e-12);
    }
  }
  EXPECT_TRUE(driving);
  EXPECT_NEAR(turned, 2 * kPi, 1e-3);  // one full turn; the drive ahead is straight
  const Pose2& end = samples->back().pose;
  EXPECT_NEAR(end.x, start.x + std::cos(0.4), 0.021);  // then 1 m ahead
  EXPECT_NEAR(end.y, start.y + std::sin(0.4), 0.021);
}

// A start facing a corner: the plain trial drives into the corner and stops; the active one
// turns towards the most open heading, drives its full metre out into the room and turns again
// there.
TEST(RouteFollowerTest, ActiveTrialLeavesTheCornerAndLooksAgain) {
  const World world = RouteRoom();
  const Scene scene(world);
  RouteSpec trial;
  trial.kind = RouteSpec::Kind::kTrial;
  const Pose2 start(0.6, 0.6, -0.75 * kPi);
  const auto stuck = GenerateTrajectory(scene, world.robot, trial, start);
  ASSERT_TRUE(stuck.ok()) << stuck.status().message();
  EXPECT_LT((stuck->back().pose.translation() - start.translation()).norm(), 0.6);

  TrajectoryOptions active;
  active.trial.face_most_open = true;
  active.trial.rotation_after_radians = 2 * kPi;
  const auto samples = GenerateTrajectory(scene, world.robot, trial, start, active);
  ASSERT_TRUE(samples.ok()) << samples.status().message();
  const Pose2& end = samples->back().pose;
  EXPECT_NEAR((end.translation() - start.translation()).norm(), 1.0, 0.021);
  const double drive_heading = std::atan2(end.y - start.y, end.x - start.x);
  // Out into the room: still metres of room ahead where the drive ended.
  EXPECT_GT(FreeDistanceAhead(scene, Pose2(end.x, end.y, drive_heading), world.robot.radius,
                              active.trial.stop_clearance_meters, 5.0),
            4.0);
  double turned = 0.0;
  for (std::size_t i = 1; i < samples->size(); ++i) {
    turned += AngleDifference((*samples)[i].pose.theta, (*samples)[i - 1].pose.theta);
  }
  // The full turn, the turn towards the open heading, the full turn where the drive ended.
  EXPECT_NEAR(turned, 4 * kPi + NormalizeAngle(drive_heading - start.theta), 0.05);
}

TEST(RouteFollowerTest, TrialStopsBeforeAnObstacleAhead) {
  World world = RouteRoom();
  Solid low_box;  // lower than any lidar, still in the way
  low_box.footprint.center = {3.8, 3.0};
  low_box.footprint.width = low_box.footprint.depth = 0.2;
  low_box.height = 0.1;
  world.obstacles.push_back(low_box);
  const Scene scene(world);
  RouteSpec trial;
  trial.kind = RouteSpec::Kind::kTrial;
  TrajectoryOptions options;
  const auto samples = GenerateTrajectory(scene, world.robot, trial, Pose2(3.0, 3.0, 0.0), options);
  ASSERT_TRUE(samples.ok()) << samples.status().message();
  // Box face at x = 3.7; the robot's front (radius 0.2) stops stop_clearance before it.
  const double expected = 3.7 - world.robot.radius - options.trial.stop_clearance_meters;
  EXPECT_NEAR(samples->back().pose.x, expected, 0.021);
  EXPECT_NEAR(FreeDistanceAhead(scene, Pose2(3.0, 3.0, 0.0), 0.2, 0.15, 5.0), 0.35, 1e-9);
}

TEST(RouteFollowerTest, RouteThroughAWallIsAnError) {
  World world = RouteRoom();
  world.walls.push_back({{5, 0}, {5, 3}});
  const Scene scene(world);
  const auto samples = GenerateTrajectory(scene, world.robot, RouteSpec{}, world.robot.start);
  ASSERT_FALSE(samples.ok());
  EXPECT_THAT(samples.status().message(), HasSubstr("on its way to mapping_route[1] (8.00, 1.00)"));
}

TEST(RouteFollowerTest, EmptyRouteAndBadStartAreErrors) {
  World world = RouteRoom();
  world.mapping_route.clear();
  const Scene scene(world);
  EXPECT_THAT(
      GenerateTrajectory(scene, world.robot, RouteSpec{}, world.robot.start).status().message(),
      HasSubstr("no mapping_route"));
  RouteSpec trial;
  trial.kind = RouteSpec::Kind::kTrial;
  EXPECT_THAT(
      GenerateTrajectory(scene, world.robot, trial, Pose2(0.1, 3.0, 0.0)).status().message(),
      HasSubstr("start pose"));
}

}  // namespace
}  // namespace semchain::sim
