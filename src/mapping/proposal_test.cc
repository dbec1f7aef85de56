#include "mapping/proposal.h"

#include <gtest/gtest.h>

#include "core/angles.h"
#include "mapping/annealing.h"
#include "mapping/ray_casting.h"
#include "mapping/testing/synthetic_world.h"

namespace semchain::mapping {
namespace {

// Samples on a regular grid whose observation log-likelihood is a known Gaussian.
ProposalEvaluation GaussianSamples(const Eigen::Vector3d& mean, const Eigen::Vector3d& sigma,
                                   double half_width, double half_angle, int steps) {
  ProposalEvaluation evaluation;
  evaluation.matched = true;
  evaluation.mode = Pose2(1.0, 2.0, 0.5);
  evaluation.log_volume = std::log(8.0 * half_width * half_width * half_angle);
  for (int i = 0; i < steps; ++i) {
    for (int j = 0; j < steps; ++j) {
      for (int k = 0; k < steps; ++k) {
        const double u = -1.0 + 2.0 * (i + 0.5) / steps, v = -1.0 + 2.0 * (j + 0.5) / steps,
                     w = -1.0 + 2.0 * (k + 0.5) / steps;
        const Eigen::Vector3d offset(half_width * u, half_width * v, half_angle * w);
        const Eigen::Vector3d z = (offset - mean).cwiseQuotient(sigma);
        evaluation.samples.push_back({Pose2(1.0 + offset.x(), 2.0 + offset.y(), 0.5 + offset.z()),
                                      -0.5 * z.squaredNorm(), 0.0});
      }
    }
  }
  return evaluation;
}

TEST(FitProposalTest, RecoversMeanCovarianceAndNormaliser) {
  const Eigen::Vector3d mean(0.002, -0.001, 0.0005), sigma(0.004, 0.003, 0.002);
  const ProposalEvaluation evaluation = GaussianSamples(mean, sigma, 0.02, 0.01, 30);
  ProposalOptions options;
  options.min_sigma_meters = 1e-9;
  options.min_sigma_radians = 1e-9;
  const GaussianFit fit = FitProposal(evaluation, 1.0, 0.0, options);
  EXPECT_NEAR(fit.mean.x(), 1.0 + mean.x(), 1e-5);
  EXPECT_NEAR(fit.mean.y(), 2.0 + mean.y(), 1e-5);
  EXPECT_NEAR(fit.mean.z(), 0.5 + mean.z(), 1e-5);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(std::sqrt(fit.covariance(i, i)), sigma[i], 2e-4);
  // η = ∫ exp(-½ zᵀz) dx = (2π)^{3/2} σx σy σθ (eq. 5 with a flat motion term).
  const double expected = std::log(std::pow(2.0 * kPi, 1.5) * sigma.prod());
  EXPECT_NEAR(fit.log_normalizer, expected, 0.02);
}

TEST(FitProposalTest, AnnealingExponentWidensTheProposal) {
  const ProposalEvaluation evaluation = GaussianSamples(
      Eigen::Vector3d::Zero(), Eigen::Vector3d(0.003, 0.003, 0.002), 0.02, 0.01, 20);
  const ProposalOptions options;
  const GaussianFit plain = FitProposal(evaluation, 1.0, 1.0, options);
  const GaussianFit annealed = FitProposal(evaluation, 1.0 - 0.6, 0.6, options);  // eq. 6
  EXPECT_GT(annealed.covariance(0, 0), 2.0 * plain.covariance(0, 0));
}

TEST(FitProposalTest, SamplesFollowTheFittedGaussian) {
  GaussianFit fit;
  fit.mean = Eigen::Vector3d(1.0, -1.0, 0.2);
  fit.covariance = Eigen::Vector3d(0.01, 0.0004, 0.0001).asDiagonal();
  Rng rng = MakeRng(11);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sum_sq = Eigen::Vector3d::Zero();
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const Pose2 p = SampleGaussian(fit, rng);
    const Eigen::Vector3d v(p.x, p.y, p.theta);
    sum += v;
    sum_sq += (v - fit.mean).cwiseAbs2();
  }
  EXPECT_TRUE((sum / n).isApprox(fit.mean, 1e-2));
  EXPECT_NEAR(std::sqrt(sum_sq.x() / n), 0.1, 0.003);
  EXPECT_NEAR(std::sqrt(sum_sq.y() / n), 0.02, 0.0006);
}

TEST(EvaluateProposalTest, ScanMatchedModeIsNearTheTruth) {
  const auto world = testing::RoomWorld();
  OccupancyGrid grid;
  for (const Pose2& pose : {Pose2(0, 0, 0), Pose2(-2, 1, kPi), Pose2(2, -1, kPi / 2)}) {
    InsertScan(PrepareScan(testing::SimulateScan(world, pose), Pose2(), {}), pose, &grid);
  }
  const Pose2 previous(0.0, 0.0, 0.0), truth(0.5, 0.1, 0.1);
  const Pose2 odometry_increment(0.54, 0.07, 0.13);  // noisy odometry
  const MatchPoints points =
      SelectMatchPoints(PrepareScan(testing::SimulateScan(world, truth), Pose2(), {}), 30.0);
  const MotionModel motion({});
  Rng rng = MakeRng(1);
  const LikelihoodField field(grid, {});
  const ProposalEvaluation evaluation = EvaluateProposal(
      field, points, motion, previous, motion.Step(odometry_increment), {}, {}, rng);
  ASSERT_TRUE(evaluation.matched);
  EXPECT_NEAR(evaluation.mode.x, truth.x, 0.01);
  EXPECT_NEAR(evaluation.mode.y, truth.y, 0.01);
  EXPECT_NEAR(evaluation.mode.theta, truth.theta, 0.005);
  EXPECT_EQ(evaluation.samples.size(), 17u);  // the mode and K = 16
  // Flat ground truth for the annealing rule: a sharp match votes "observation".
  EXPECT_EQ(ClassifyStep({}, evaluation, {}, motion.Sigmas(odometry_increment)),
            DominantModel::kObservation);
}

TEST(AnnealingTest, RulesPickAlpha) {
  AnnealingOptions options;
  using D = DominantModel;
  EXPECT_DOUBLE_EQ(ChooseAlpha(options, {D::kObservation, D::kObservation, D::kMotion}), 0.02);
  EXPECT_DOUBLE_EQ(ChooseAlpha(options, {D::kMotion, D::kObservation, D::kMotion}), 0.6);
  options.rule = "fixed";
  options.alpha = 0.3;
  EXPECT_DOUBLE_EQ(ChooseAlpha(options, {D::kMotion}), 0.3);
  std::string error;
  options.rule = "sometimes";
  EXPECT_FALSE(options.Validate(&error));
}

}  // namespace
}  // namespace semchain::mapping
