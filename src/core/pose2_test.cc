#include "core/pose2.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/angles.h"
#include "core/rng.h"

namespace semchain {
namespace {

void ExpectPoseNear(const Pose2& a, const Pose2& b, double tolerance = 1e-12) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(AngleDifference(a.theta, b.theta), 0.0, tolerance);
}

// A pose drawn one coordinate a statement, θ first: a constructor's arguments are evaluated in
// an unspecified order (GCC last to first), and a seed must give the same poses everywhere.
Pose2 RandomPose(Rng& rng, std::uniform_real_distribution<double>& coordinate,
                 std::uniform_real_distribution<double>& angle) {
  const double theta = angle(rng), y = coordinate(rng), x = coordinate(rng);
  return Pose2(x, y, theta);
}

TEST(AnglesTest, NormalizesIntoHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(NormalizeAngle(kPi), kPi);
  EXPECT_DOUBLE_EQ(NormalizeAngle(-kPi), kPi);
  EXPECT_NEAR(NormalizeAngle(3.0 * kPi / 2.0), -kPi / 2.0, 1e-15);
  EXPECT_NEAR(NormalizeAngle(-7.0 * kPi + 0.25), 0.25 - kPi, 1e-12);
  EXPECT_NEAR(AngleDifference(DegToRad(-179.0), DegToRad(179.0)), DegToRad(2.0), 1e-12);
}

TEST(Pose2Test, ComposeMatchesHandComputedExample) {
  // Robot at (1, 2) facing +y; a point 1 m ahead and 0.5 m to its left lies at (0.5, 3).
  const Pose2 robot(1.0, 2.0, kPi / 2.0);
  const Eigen::Vector2d point = robot * Eigen::Vector2d(1.0, 0.5);
  EXPECT_NEAR(point.x(), 0.5, 1e-12);
  EXPECT_NEAR(point.y(), 3.0, 1e-12);
  ExpectPoseNear(robot * Pose2(1.0, 0.5, kPi / 2.0), Pose2(0.5, 3.0, kPi));
}

TEST(Pose2Test, IsometryMapsPointsAsThePose) {
  const Eigen::Isometry2d robot = Pose2(1.0, 2.0, kPi / 2.0).ToIsometry();
  const Eigen::Vector2d point = robot * Eigen::Vector2d(1.0, 0.5);
  EXPECT_NEAR(point.x(), 0.5, 1e-12);
  EXPECT_NEAR(point.y(), 3.0, 1e-12);
  Rng rng = MakeRng(3);
  std::uniform_real_distribution<double> coordinate(-10.0, 10.0);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  for (int i = 0; i < 100; ++i) {
    const Pose2 pose = RandomPose(rng, coordinate, angle);
    const double py = coordinate(rng), px = coordinate(rng);  // GCC's argument order
    const Eigen::Vector2d p(px, py);
    EXPECT_LT(((pose.ToIsometry() * p) - pose * p).norm(), 1e-12);
  }
}

TEST(Pose2Test, InverseAndBetweenAreConsistent) {
  Rng rng = MakeRng(7);
  std::uniform_real_distribution<double> coordinate(-10.0, 10.0);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  for (int i = 0; i < 100; ++i) {
    const Pose2 a = RandomPose(rng, coordinate, angle);
    const Pose2 b = RandomPose(rng, coordinate, angle);
    ExpectPoseNear(a * a.Inverse(), Pose2());
    ExpectPoseNear(a * a.Between(b), b, 1e-9);
    ExpectPoseNear(a.Between(b).Inverse(), b.Between(a), 1e-9);
  }
}

TEST(Pose2Test, InterpolateTakesTheShorterArc) {
  const Pose2 a(0.0, 0.0, DegToRad(170.0));
  const Pose2 b(2.0, 4.0, DegToRad(-170.0));
  const Pose2 mid = Interpolate(a, b, 0.5);
  EXPECT_NEAR(mid.x, 1.0, 1e-12);
  EXPECT_NEAR(mid.y, 2.0, 1e-12);
  EXPECT_NEAR(std::abs(mid.theta), kPi, 1e-12);
  ExpectPoseNear(Interpolate(a, b, 0.0), a);
  ExpectPoseNear(Interpolate(a, b, 1.0), b);
}

TEST(RngTest, SameSeedAndStreamGiveSameSequence) {
  Rng a = MakeRng(42, 3);
  Rng b = MakeRng(42, 3);
  Rng c = MakeRng(42, 4);
  const auto first_a = a();
  EXPECT_EQ(first_a, b());
  EXPECT_NE(first_a, c());
}

}  // namespace
}  // namespace semchain
