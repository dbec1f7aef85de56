#include "core/transforms.h"

#include <gtest/gtest.h>

#include "core/angles.h"

namespace semchain {
namespace {

TEST(TransformsTest, OpticalAxisPointsForwardOnTheRobot) {
  const Eigen::Isometry3d robot_from_camera = RobotFromOpticalCamera(0.1, 0.0, 0.5, 0.0, 0.0);
  // A point 2 m along the optical axis, 0.3 m right (x) and 0.2 m down (y) in the image.
  const Eigen::Vector3d p = CameraToRobot(robot_from_camera, {0.3, 0.2, 2.0});
  EXPECT_NEAR(p.x(), 2.1, 1e-12);   // forward
  EXPECT_NEAR(p.y(), -0.3, 1e-12);  // right is -y
  EXPECT_NEAR(p.z(), 0.3, 1e-12);   // down from the 0.5 m mount
}

TEST(TransformsTest, CameraToGridChainMatchesHandComputation) {
  const Eigen::Isometry3d robot_from_camera = RobotFromOpticalCamera(0.0, 0.0, 0.5, 0.0, 0.0);
  const Pose2 robot(2.0, 1.0, kPi / 2.0);  // facing +y
  const Eigen::Vector3d world =
      RobotToWorld(robot, CameraToRobot(robot_from_camera, {0.0, 0.0, 3.0}));
  EXPECT_NEAR(world.x(), 2.0, 1e-12);
  EXPECT_NEAR(world.y(), 4.0, 1e-12);
  EXPECT_NEAR(world.z(), 0.5, 1e-12);
  const Eigen::Vector2i cell = WorldToGrid(world.head<2>(), 0.05);
  EXPECT_EQ(cell, Eigen::Vector2i(40, 80));
  const Eigen::Vector2i offset_cell = WorldToGrid({-0.01, 0.26}, 0.05, {-1.0, 0.0});
  EXPECT_EQ(offset_cell, Eigen::Vector2i(19, 5));
  EXPECT_TRUE(GridToWorld({19, 5}, 0.05, {-1.0, 0.0}).isApprox(Eigen::Vector2d(-0.025, 0.275)));
}

TEST(TransformsTest, PitchedCameraLooksAtTheFloor) {
  // Pitched down by 45 degrees at 1 m height: the optical axis hits the floor 1 m ahead.
  const Eigen::Isometry3d robot_from_camera =
      RobotFromOpticalCamera(0.0, 0.0, 1.0, 0.0, DegToRad(45.0));
  const Eigen::Vector3d p = CameraToRobot(robot_from_camera, {0.0, 0.0, std::sqrt(2.0)});
  EXPECT_NEAR(p.x(), 1.0, 1e-12);
  EXPECT_NEAR(p.z(), 0.0, 1e-12);
}

}  // namespace
}  // namespace semchain
