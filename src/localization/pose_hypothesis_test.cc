#include "localization/pose_hypothesis.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/angles.h"

namespace semchain::localization {
namespace {

PoseHypothesis Hypothesis(double x, double y, double theta, double weight = 1.0) {
  PoseHypothesis h;
  h.pose = Pose2(x, y, theta);
  h.covariance = Eigen::Vector3d(0.04, 0.09, 0.01).asDiagonal();
  h.weight = weight;
  return h;
}

TEST(PosePriorTest, GaussianMaxOverHypothesesWithAFloor) {
  const PosePrior prior({Hypothesis(0, 0, 0), Hypothesis(5, 0, kPi, 0.5)}, 0.05);
  EXPECT_NEAR(prior.Probability(Pose2(0, 0, 0)), 1.0, 1e-12);
  EXPECT_NEAR(prior.Probability(Pose2(0.2, 0.0, 0.0)), std::exp(-0.5), 1e-12);  // 1 σ in x
  EXPECT_NEAR(prior.Probability(Pose2(0.0, 0.0, 0.1)), std::exp(-0.5), 1e-12);  // 1 σ in θ
  // Headings wrap: −π + 0.1 is 0.1 from π.
  EXPECT_NEAR(prior.Probability(Pose2(5.0, 0.0, -kPi + 0.1)), 0.5 * std::exp(-0.5), 1e-12);
  EXPECT_NEAR(prior.Probability(Pose2(20.0, 20.0, 0.0)), 0.05, 1e-12);  // far: the floor
}

TEST(PoseHypothesisTest, SamplesHaveTheHypothesisMomentsAndBadListsAreRejected) {
  PoseHypothesis h = Hypothesis(1, 2, 3);
  h.covariance(0, 1) = h.covariance(1, 0) = 0.03;
  Rng rng = MakeRng(3);
  const int n = 100000;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Pose2 p = SamplePose(h, rng);
    const Eigen::Vector3d e(p.x - 1, p.y - 2, AngleDifference(p.theta, 3));
    sum += e;
    outer += e * e.transpose();
  }
  EXPECT_LT((sum / n).norm(), 0.003);
  EXPECT_TRUE((outer / n).isApprox(h.covariance, 0.03)) << outer / n;
  EXPECT_FALSE(ValidateHypotheses({}).ok());
  PoseHypothesis bad = h;
  bad.covariance(2, 2) = -1.0;
  EXPECT_FALSE(ValidateHypotheses({h, bad}).ok());
  bad = h;
  bad.weight = 0.0;
  EXPECT_FALSE(ValidateHypotheses({bad}).ok());
}

}  // namespace
}  // namespace semchain::localization
