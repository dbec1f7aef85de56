#include "eval/rpe.h"

#include <gtest/gtest.h>

#include "core/angles.h"

namespace semchain::eval {
namespace {

// A straight path along x, a pose a metre, stamped a second apart.
std::vector<StampedPose> StraightPath(int poses) {
  std::vector<StampedPose> path;
  for (int i = 0; i < poses; ++i) path.push_back({1.0 * i, Pose2(1.0 * i, 0.0, 0.0)});
  return path;
}

RpeOptions Stretches(std::vector<double> lengths) {
  RpeOptions options;
  options.travel_meters = std::move(lengths);
  return options;
}

TEST(RpeTest, TheTruthAgainstItselfHasNoError) {
  const std::vector<StampedPose> truth = StraightPath(101);
  const Result<RpeResult> result = EvaluateRpe(truth, truth, Stretches({10.0}));
  ASSERT_TRUE(result.ok()) << result.status().message();
  ASSERT_EQ(result->stretches.size(), 1u);
  EXPECT_EQ(result->stretches[0].stretches, 91u);  // from poses 0..90 to 10..100
  EXPECT_EQ(result->stretches[0].translation_max_m, 0.0);
  EXPECT_EQ(result->stretches[0].rotation_max_deg, 0.0);
}

// An estimate 1 % short: every 10 m stretch is 0.1 m short along the track, and not turned.
TEST(RpeTest, AScaleErrorIsAlongTheTrack) {
  const std::vector<StampedPose> truth = StraightPath(101);
  std::vector<StampedPose> estimate = truth;
  for (StampedPose& pose : estimate) pose.pose.x *= 0.99;
  const Result<RpeResult> result = EvaluateRpe(estimate, truth, Stretches({10.0, 50.0}));
  ASSERT_TRUE(result.ok());
  EXPECT_NEAR(result->stretches[0].along_track_median_m, -0.1, 1e-9);
  EXPECT_NEAR(result->stretches[0].translation_max_m, 0.1, 1e-9);
  EXPECT_NEAR(result->stretches[1].along_track_median_m, -0.5, 1e-9);
  EXPECT_EQ(result->stretches[1].stretches, 51u);
  EXPECT_NEAR(result->stretches[1].rotation_max_deg, 0.0, 1e-9);
}

// A heading drift of d a metre turns every L metre stretch by d·L, wherever it starts.
TEST(RpeTest, AHeadingDriftGrowsWithTheStretch) {
  const std::vector<StampedPose> truth = StraightPath(101);
  const double drift = DegToRad(0.05);
  std::vector<StampedPose> estimate = {truth[0]};
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const Pose2 step(1.0, 0.0, drift);
    estimate.push_back({truth[i].timestamp, estimate.back().pose * step});
  }
  const Result<RpeResult> result = EvaluateRpe(estimate, truth, Stretches({10.0, 40.0}));
  ASSERT_TRUE(result.ok());
  EXPECT_NEAR(result->stretches[0].rotation_median_deg, 0.5, 1e-9);
  EXPECT_NEAR(result->stretches[0].rotation_max_deg, 0.5, 1e-9);
  EXPECT_NEAR(result->stretches[1].rotation_median_deg, 2.0, 1e-9);
  // The chord of the bent stretch is off sideways by about L²·d/2.
  EXPECT_NEAR(result->stretches[1].translation_median_m, 40.0 * 40.0 * drift / 2.0, 0.05);
}

TEST(RpeTest, AStretchLongerThanThePathHasNone) {
  const std::vector<StampedPose> truth = StraightPath(11);
  const Result<RpeResult> result = EvaluateRpe(truth, truth, Stretches({100.0}));
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result->stretches[0].stretches, 0u);
}

TEST(RpeTest, BadLengthsAndUnpairedPosesAreErrors) {
  const std::vector<StampedPose> truth = StraightPath(11);
  EXPECT_FALSE(EvaluateRpe(truth, truth, Stretches({0.0})).ok());
  std::vector<StampedPose> later = truth;
  for (StampedPose& pose : later) pose.timestamp += 1000.0;
  const Result<RpeResult> unpaired = EvaluateRpe(later, truth);
  ASSERT_FALSE(unpaired.ok());
  EXPECT_NE(unpaired.status().message().find("truth pose"), std::string::npos);
}

}  // namespace
}  // namespace semchain::eval
