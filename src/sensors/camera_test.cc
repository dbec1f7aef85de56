#include "sensors/camera.h"

#include <gtest/gtest.h>

#include "core/angles.h"

namespace semchain {
namespace {

TEST(PinholeCameraTest, FovEdgesProjectToImageBorders) {
  const PinholeCamera camera = PinholeCamera::FromFov(320, 240, DegToRad(90.0));
  // At 45 degrees off-axis the ray leaves through the left/right image border.
  EXPECT_NEAR(camera.Project({1.0, 0.0, 1.0}).x(), 319.5, 1e-9);
  EXPECT_NEAR(camera.Project({-1.0, 0.0, 1.0}).x(), -0.5, 1e-9);
  EXPECT_NEAR(camera.fx, 160.0, 1e-12);
}

TEST(PinholeCameraTest, BackprojectInvertsProject) {
  const PinholeCamera camera = PinholeCamera::FromFov(640, 480, DegToRad(60.0));
  const Eigen::Vector3d point(0.4, -0.3, 2.5);
  const Eigen::Vector2d pixel = camera.Project(point);
  EXPECT_TRUE(camera.Backproject(pixel.x(), pixel.y(), point.z()).isApprox(point, 1e-12));
  EXPECT_TRUE(camera.Contains(pixel.x(), pixel.y()));
  EXPECT_FALSE(camera.Contains(-1.0, 10.0));
}

}  // namespace
}  // namespace semchain
