#include "localization/odometry_motion_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/angles.h"

namespace semchain::localization {
namespace {

TEST(OdometryMotionTest, DecomposesIntoRotationTranslationRotation) {
  const OdometryMotion u = OdometryMotion::Between(Pose2(1, 1, 0), Pose2(1, 3, kPi));
  EXPECT_NEAR(u.rot1, kPi / 2, 1e-12);
  EXPECT_NEAR(u.trans, 2.0, 1e-12);
  EXPECT_NEAR(u.rot2, kPi / 2, 1e-12);
  // Driving backwards: the decomposition turns by π, the noise sees no rotation.
  const OdometryMotion back = OdometryMotion::Between(Pose2(0, 0, 0), Pose2(-1, 0, 0));
  EXPECT_NEAR(std::abs(back.rot1), kPi, 1e-12);
  EXPECT_NEAR(back.rot1_noise, 0.0, 1e-12);
}

// Table 5.6: the travelled distance is δtrans − ε with Var ε = α3 δtrans² + α4 (δrot1² + δrot2²);
// the heading change is δrot1 + δrot2 − ε1 − ε2 with variances α1 δrot² + α2 δtrans² each.
TEST(OdometryMotionModelTest, SampleMomentsMatchTheAnalyticMeanAndVariance) {
  const OdometryMotionNoise noise{0.05, 0.02, 0.1, 0.03};
  const OdometryMotionModel model(noise);
  const Pose2 from(2.0, -1.0, 0.3);
  const Pose2 to(3.0, -0.5, 0.9);
  const OdometryMotion u = OdometryMotion::Between(from, to);
  const Pose2 start(-4.0, 2.0, 1.0);  // a particle elsewhere: the same motion in its frame
  Rng rng = MakeRng(11);
  const int n = 200000;
  double sum_d = 0, sum_d2 = 0, sum_t = 0, sum_t2 = 0;
  for (int i = 0; i < n; ++i) {
    const Pose2 x = model.Sample(start, u, rng);
    const double d = std::hypot(x.x - start.x, x.y - start.y);
    const double t = AngleDifference(x.theta, start.theta);
    sum_d += d;
    sum_d2 += d * d;
    sum_t += t;
    sum_t2 += t * t;
  }
  const double mean_d = sum_d / n, var_d = sum_d2 / n - mean_d * mean_d;
  const double mean_t = sum_t / n, var_t = sum_t2 / n - mean_t * mean_t;
  const double trans_var =
      noise.alpha3 * u.trans * u.trans + noise.alpha4 * (u.rot1 * u.rot1 + u.rot2 * u.rot2);
  const double rot_var =
      noise.alpha1 * (u.rot1 * u.rot1 + u.rot2 * u.rot2) + 2.0 * noise.alpha2 * u.trans * u.trans;
  EXPECT_NEAR(mean_d, u.trans, 3e-4);
  EXPECT_NEAR(var_d, trans_var, 0.02 * trans_var);
  EXPECT_NEAR(mean_t, AngleDifference(to.theta, from.theta), 3e-4);
  EXPECT_NEAR(var_t, rot_var, 0.02 * rot_var);
}

// nav2's DifferentialMotionModel on a turn in place whose odometry also shifted 3 cm sideways:
// above 1 cm the shift sets δrot1 (about 90°), and both rotations then drive the noise through
// min(|δ|, |π − δ|): σ_rot1 = √(α1 n1² + α2 t²), σ_trans = √(α3 t² + α4 (n1² + n2²)),
// σ_rot2 = √(α1 n2² + α2 t²).
TEST(OdometryMotionModelTest, SigmasOfATurnInPlaceWithASidewaysShiftAreNav2s) {
  const OdometryMotionModel model({0.2, 0.2, 0.2, 0.2});
  const OdometryMotion u = OdometryMotion::Between(Pose2(0, 0, 0), Pose2(0.0, 0.03, 0.2));
  EXPECT_NEAR(u.rot1, kPi / 2, 1e-12);
  EXPECT_NEAR(u.trans, 0.03, 1e-12);
  EXPECT_NEAR(u.rot2, 0.2 - kPi / 2, 1e-12);
  const double n1 = kPi / 2, n2 = kPi / 2 - 0.2;
  EXPECT_NEAR(u.rot1_noise, n1, 1e-12);
  EXPECT_NEAR(u.rot2_noise, n2, 1e-12);
  EXPECT_NEAR(model.Rot1Sigma(u), std::sqrt(0.2 * n1 * n1 + 0.2 * 0.0009), 1e-12);
  EXPECT_NEAR(model.TransSigma(u), std::sqrt(0.2 * 0.0009 + 0.2 * (n1 * n1 + n2 * n2)), 1e-12);
  EXPECT_NEAR(model.Rot2Sigma(u), std::sqrt(0.2 * n2 * n2 + 0.2 * 0.0009), 1e-12);
  // Below 1 cm δrot1 is 0 and the whole turn is δrot2.
  const OdometryMotion small = OdometryMotion::Between(Pose2(0, 0, 0), Pose2(0.0, 0.009, 0.2));
  EXPECT_EQ(small.rot1, 0.0);
  EXPECT_NEAR(small.rot2, 0.2, 1e-12);
  EXPECT_NEAR(model.TransSigma(small), std::sqrt(0.2 * 0.009 * 0.009 + 0.2 * 0.04), 1e-12);
}

TEST(OdometryMotionModelTest, NoMotionNoNoise) {
  const OdometryMotionModel model({0.2, 0.2, 0.2, 0.2});
  const OdometryMotion u = OdometryMotion::Between(Pose2(1, 2, 3), Pose2(1, 2, 3));
  Rng rng = MakeRng(1);
  const Pose2 x = model.Sample(Pose2(5, 6, 0.5), u, rng);
  EXPECT_DOUBLE_EQ(x.x, 5.0);
  EXPECT_DOUBLE_EQ(x.y, 6.0);
  EXPECT_DOUBLE_EQ(x.theta, 0.5);
}

}  // namespace
}  // namespace semchain::localization
