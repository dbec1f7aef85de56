#include "sim/odometry_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/angles.h"

namespace semchain::sim {
namespace {

// A curvy true trajectory: an arc, a rotation in place and a straight leg.
std::vector<Pose2> CurvyTrajectory() {
  std::vector<Pose2> poses;
  for (int i = 0; i <= 40; ++i) {
    const double a = 0.05 * i;
    poses.emplace_back(1.0 + std::sin(a), 2.0 - std::cos(a) + 1.0, a);
  }
  for (int i = 1; i <= 20; ++i) poses.emplace_back(poses.back().x, poses.back().y, 2.0 + 0.1 * i);
  for (int i = 1; i <= 20; ++i) {
    const Pose2& p = poses.back();
    poses.emplace_back(p.x + 0.05 * std::cos(p.theta), p.y + 0.05 * std::sin(p.theta), p.theta);
  }
  return poses;
}

struct Moments {
  double mean = 0.0;
  double variance = 0.0;
};

Moments Measure(const std::vector<double>& values) {
  Moments m;
  for (double v : values) m.mean += v;
  m.mean /= static_cast<double>(values.size());
  for (double v : values) m.variance += (v - m.mean) * (v - m.mean);
  m.variance /= static_cast<double>(values.size() - 1);
  return m;
}

TEST(OdometryModelTest, IncrementRoundTrip) {
  const Pose2 from(1.0, 2.0, 0.3), to(1.5, 2.8, -2.9);
  const OdometryIncrement increment = ComputeIncrement(from, to);
  EXPECT_NEAR(increment.trans, std::hypot(0.5, 0.8), 1e-12);
  const Pose2 back = ApplyIncrement(from, increment);
  EXPECT_NEAR(back.x, to.x, 1e-12);
  EXPECT_NEAR(back.y, to.y, 1e-12);
  EXPECT_NEAR(AngleDifference(back.theta, to.theta), 0.0, 1e-12);
  // A rotation in place is all δrot2.
  const OdometryIncrement turn = ComputeIncrement(from, Pose2(1.0, 2.0, 1.3));
  EXPECT_EQ(turn.rot1, 0.0);
  EXPECT_EQ(turn.trans, 0.0);
  EXPECT_NEAR(turn.rot2, 1.0, 1e-12);
}

TEST(OdometryModelTest, ZeroNoiseOdometryEqualsTruth) {
  const std::vector<Pose2> truth = CurvyTrajectory();
  OdometrySimulator odometry({0.0, 0.0, 0.0, 0.0}, truth.front());
  Rng rng = MakeRng(3, 2);
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const Pose2 odom = odometry.Step(truth[i], rng);
    EXPECT_NEAR(odom.x, truth[i].x, 1e-9) << i;
    EXPECT_NEAR(odom.y, truth[i].y, 1e-9) << i;
    EXPECT_NEAR(AngleDifference(odom.theta, truth[i].theta), 0.0, 1e-9) << i;
  }
}

// A robot driving a 10 m straight line and then turning a full circle in place, with odometry
// that over-reads distance by 2 % and under-reads turns by 3 % and no noise: it reports 10.2 m
// and a turn of 0.97 · 2π.
TEST(OdometryModelTest, ScaleErrorOverReadsEveryMotionByItsFraction) {
  OdometrySimulator odometry({0.0, 0.0, 0.0, 0.0}, Pose2(), {0.02, -0.03});
  Rng rng = MakeRng(3, 2);
  for (int i = 1; i <= 100; ++i) odometry.Step(Pose2(0.1 * i, 0.0, 0.0), rng);
  EXPECT_NEAR(odometry.pose().x, 10.2, 1e-9);
  EXPECT_NEAR(odometry.pose().y, 0.0, 1e-9);
  double turned = 0.0;
  Pose2 previous = odometry.pose();
  for (int i = 1; i <= 63; ++i) {
    const Pose2& now = odometry.Step(Pose2(10.0, 0.0, 0.1 * i), rng);
    turned += AngleDifference(now.theta, previous.theta);
    previous = now;
  }
  EXPECT_NEAR(turned, 0.97 * 6.3, 1e-9);
  EXPECT_NEAR(odometry.pose().x, 10.2, 1e-9);  // turning in place moves nothing
}

TEST(OdometryModelTest, OdometryStartsAtTheTrueStartPose) {
  const Pose2 start(4.0, -1.0, 2.0);
  const OdometrySimulator odometry({0.1, 0.1, 0.1, 0.1}, start);
  EXPECT_EQ(odometry.pose().x, start.x);
  EXPECT_EQ(odometry.pose().y, start.y);
  EXPECT_EQ(odometry.pose().theta, start.theta);
}

// Pure translation by d: heading error = -(e_rot1 + e_rot2), var 2 α2 d²; error along the
// motion ≈ -e_trans, var α3 d² (table 5.6 with δrot1 = δrot2 = 0).
TEST(OdometryModelTest, TranslationNoiseScalesAsTheAlphaModel) {
  const std::array<double, 4> alphas = {0.3, 0.005, 0.05, 0.4};
  const double d = 0.8;
  Rng rng = MakeRng(11, 2);
  std::vector<double> along, heading;
  for (int k = 0; k < 40000; ++k) {
    OdometrySimulator odometry(alphas, Pose2());
    const Pose2 odom = odometry.Step(Pose2(d, 0.0, 0.0), rng);
    along.push_back(odom.x - d);
    heading.push_back(odom.theta);
  }
  const Moments a = Measure(along), h = Measure(heading);
  EXPECT_NEAR(a.mean, -d * (alphas[1] * d * d) / 2.0, 0.004);  // cos(δrot1) < 1 shortens x
  EXPECT_NEAR(a.variance, alphas[2] * d * d, 0.03 * alphas[2] * d * d);
  EXPECT_NEAR(h.variance, 2.0 * alphas[1] * d * d, 0.03 * 2.0 * alphas[1] * d * d);
}

// Rotation in place by φ: heading error = -e_rot2, var α1 φ²; a spurious translation of var
// α4 φ² appears along the start heading (δrot1 = 0 and its noise has zero variance).
TEST(OdometryModelTest, RotationNoiseScalesAsTheAlphaModel) {
  const std::array<double, 4> alphas = {0.05, 0.3, 0.3, 0.02};
  const double phi = 1.2;
  Rng rng = MakeRng(12, 2);
  std::vector<double> heading, along, across;
  for (int k = 0; k < 40000; ++k) {
    OdometrySimulator odometry(alphas, Pose2(0.0, 0.0, 0.0));
    const Pose2 odom = odometry.Step(Pose2(0.0, 0.0, phi), rng);
    heading.push_back(AngleDifference(odom.theta, phi));
    along.push_back(odom.x);
    across.push_back(odom.y);
  }
  EXPECT_NEAR(Measure(heading).variance, alphas[0] * phi * phi, 0.03 * alphas[0] * phi * phi);
  EXPECT_NEAR(Measure(along).variance, alphas[3] * phi * phi, 0.03 * alphas[3] * phi * phi);
  EXPECT_NEAR(Measure(across).variance, 0.0, 1e-12);
}

// Doubling a motion doubles the error std (the α model is proportional to the motion).
TEST(OdometryModelTest, ErrorGrowsLinearlyWithTheMotion) {
  const std::array<double, 4> alphas = {0.0, 0.0, 0.04, 0.0};
  double variance[2] = {0.0, 0.0};
  for (int scale = 1; scale <= 2; ++scale) {
    Rng rng = MakeRng(13, 2);
    std::vector<double> errors;
    for (int k = 0; k < 20000; ++k) {
      OdometrySimulator odometry(alphas, Pose2());
      errors.push_back(odometry.Step(Pose2(0.5 * scale, 0.0, 0.0), rng).x - 0.5 * scale);
    }
    variance[scale - 1] = Measure(errors).variance;
  }
  EXPECT_NEAR(std::sqrt(variance[1] / variance[0]), 2.0, 1e-9);  // same draws, scaled
}

}  // namespace
}  // namespace semchain::sim
