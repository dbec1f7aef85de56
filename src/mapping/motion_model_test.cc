#include "mapping/motion_model.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/angles.h"

namespace semchain::mapping {
namespace {

// The empirical covariance of the noise of 'ends' around 'prediction', in its frame.
Eigen::Matrix3d EmpiricalCovariance(const std::vector<Pose2>& ends, const Pose2& prediction) {
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Pose2& end : ends) {
    const Pose2 e = prediction.Between(end);
    const Eigen::Vector3d v(e.x, e.y, e.theta);
    covariance += v * v.transpose();
  }
  return covariance / static_cast<double>(ends.size());
}

// GMapping draws the motion noise at every odometry reading. Fifteen readings of a curve
// (7 cm and 2° each), drawn one by one 20000 times, spread as the accumulated covariance says,
// the correlations the heading noise gives the lateral position included.
TEST(MotionModelTest, AccumulatedCovarianceMatchesReadingByReadingDraws) {
  const MotionModel model({0.1, 0.1, 0.2, 0.2});
  const Pose2 reading(0.07, 0.0, DegToRad(2.0));
  constexpr int kReadings = 15;
  MotionStep total;
  for (int i = 0; i < kReadings; ++i) model.Accumulate(reading, &total);

  Rng rng(7);
  std::vector<Pose2> ends;
  for (int n = 0; n < 20000; ++n) {
    Pose2 pose;
    for (int i = 0; i < kReadings; ++i) pose = model.Sample(pose, reading, rng);
    ends.push_back(pose);
  }
  const Eigen::Matrix3d empirical = EmpiricalCovariance(ends, total.increment);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(empirical(i, i), total.covariance(i, i), 0.05 * total.covariance(i, i)) << i;
    for (int j = 0; j < i; ++j) {
      const double scale = std::sqrt(total.covariance(i, i) * total.covariance(j, j));
      EXPECT_NEAR(empirical(i, j) / scale, total.covariance(i, j) / scale, 0.03) << i << j;
    }
  }
  // The lever arm of the heading noise is there: y and θ are strongly correlated.
  EXPECT_GT(total.covariance(1, 2) / std::sqrt(total.covariance(1, 1) * total.covariance(2, 2)),
            0.5);
  EXPECT_NEAR(total.increment.theta, DegToRad(30.0), 1e-12);
}

// n independent readings spread √n times less than one draw over their sum.
TEST(MotionModelTest, StraightReadingsSpreadWithTheSquareRootOfTheirCount) {
  const MotionModel model({0.1, 0.1, 0.2, 0.2});
  MotionStep total;
  for (int i = 0; i < 16; ++i) model.Accumulate(Pose2(0.0625, 0.0, 0.0), &total);
  const Eigen::Vector3d one_draw = model.Sigmas(Pose2(1.0, 0.0, 0.0));
  EXPECT_NEAR(std::sqrt(total.covariance(2, 2)), one_draw.z() / 4.0, 1e-12);
  EXPECT_NEAR(total.covariance(0, 0), std::pow(one_draw.x() / 4.0, 2), 1e-12);
  // y also gains the heading noise times the distance still to go.
  EXPECT_GT(total.covariance(1, 1), total.covariance(0, 0));
}

TEST(MotionModelTest, StandingStillAddsNoNoiseButTheFloorsRemain) {
  const MotionModelOptions options{0.1, 0.1, 0.2, 0.2};
  const MotionModel model(options);
  MotionStep total;
  for (int i = 0; i < 100; ++i) model.Accumulate(Pose2(), &total);
  EXPECT_EQ(total.covariance, Eigen::Matrix3d::Zero());
  const Eigen::Vector3d sigmas = model.Sigmas(total);
  EXPECT_DOUBLE_EQ(sigmas.x(), options.min_translation_sigma_meters);
  EXPECT_DOUBLE_EQ(sigmas.z(), options.min_rotation_sigma_radians);
}

// One draw over an increment (per_reading_noise off) is exactly the per-axis draw it always was,
// so configurations that keep it give the same maps for the same seed.
TEST(MotionModelTest, OneDrawOverAnIncrementIsThePerAxisGaussian) {
  const MotionModel model({});
  const Pose2 previous(1.0, -2.0, 0.3), increment(0.8, 0.1, 0.4);
  const Eigen::Vector3d sigma = model.Sigmas(increment);
  Rng a(11), b(11);
  for (int n = 0; n < 100; ++n) {
    const Pose2 drawn = model.Sample(previous, increment, a);
    std::normal_distribution<double> normal;  // a fresh one per draw, as Sample's
    const double z_theta = normal(b), z_y = normal(b), z_x = normal(b);
    const Pose2 expected =
        previous * increment * Pose2(sigma.x() * z_x, sigma.y() * z_y, sigma.z() * z_theta);
    EXPECT_EQ(drawn.x, expected.x);
    EXPECT_EQ(drawn.y, expected.y);
    EXPECT_EQ(drawn.theta, expected.theta);
    const Pose2 error = (previous * increment).Between(drawn);
    const Eigen::Vector3d e(error.x / sigma.x(), error.y / sigma.y(), error.theta / sigma.z());
    EXPECT_DOUBLE_EQ(model.LogDensity(drawn, previous, increment), -0.5 * e.squaredNorm());
  }
}

}  // namespace
}  // namespace semchain::mapping
