#include "eval/ate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/angles.h"
#include "core/rng.h"

namespace semchain::eval {
namespace {

// A seeded random walk: 'n' poses at 10 Hz.
std::vector<StampedPose> RandomWalk(int n, std::uint64_t seed) {
  Rng rng = MakeRng(seed);
  std::normal_distribution<double> step(0.0, 0.2);
  std::vector<StampedPose> poses;
  Pose2 pose;
  for (int i = 0; i < n; ++i) {
    poses.push_back({0.1 * i, pose});
    // One draw a statement, θ first: argument order is unspecified (GCC's, last to first).
    const double theta = step(rng), y = step(rng), x = 0.1 + std::abs(step(rng));
    pose = pose * Pose2(x, y, theta);
  }
  return poses;
}

TEST(AteTest, IdenticalTrajectoriesScoreZero) {
  const std::vector<StampedPose> truth = RandomWalk(50, 1);
  const Result<AteResult> result = EvaluateAte(truth, truth);
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result->poses, 50u);
  EXPECT_EQ(result->matched, 50u);
  EXPECT_EQ(result->ate_rmse_m, 0.0);
  EXPECT_EQ(result->ate_max_m, 0.0);
  EXPECT_EQ(result->rot_rmse_deg, 0.0);
}

TEST(AteTest, OneOffsetPoseGivesKnownErrors) {
  const std::vector<StampedPose> truth = {
      {0, Pose2(0, 0, 0)}, {1, Pose2(1, 0, 0)}, {2, Pose2(2, 0, 0.5)}, {3, Pose2(3, 1, 1)}};
  std::vector<StampedPose> estimate = truth;
  estimate[2].pose = Pose2(2.3, 0.4, 0.5 + DegToRad(2.0));  // 0.5 m and 2° off
  const Result<AteResult> result = EvaluateAte(estimate, truth);
  ASSERT_TRUE(result.ok());
  EXPECT_NEAR(result->ate_rmse_m, std::sqrt(0.25 / 4), 1e-12);
  EXPECT_NEAR(result->ate_mean_m, 0.5 / 4, 1e-12);
  EXPECT_NEAR(result->ate_max_m, 0.5, 1e-12);
  EXPECT_NEAR(result->rot_rmse_deg, std::sqrt(4.0 / 4), 1e-9);
}

TEST(AteTest, AlignmentRemovesARigidMotion) {
  const std::vector<StampedPose> truth = RandomWalk(80, 2);
  const Pose2 motion(3.0, -2.0, 0.7);
  std::vector<StampedPose> estimate = truth;
  for (StampedPose& p : estimate) p.pose = motion * p.pose;
  AteOptions options;
  const Result<AteResult> raw = EvaluateAte(estimate, truth, options);
  ASSERT_TRUE(raw.ok());
  EXPECT_GT(raw->ate_rmse_m, 1.0);
  EXPECT_NEAR(raw->rot_rmse_deg, RadToDeg(0.7), 1e-9);
  options.align = true;
  const Result<AteResult> aligned = EvaluateAte(estimate, truth, options);
  ASSERT_TRUE(aligned.ok());
  EXPECT_NEAR(aligned->ate_rmse_m, 0.0, 1e-9);
  EXPECT_NEAR(aligned->rot_rmse_deg, 0.0, 1e-9);
  const Pose2 inverse = motion.Inverse();
  EXPECT_NEAR(aligned->alignment.x, inverse.x, 1e-9);
  EXPECT_NEAR(aligned->alignment.y, inverse.y, 1e-9);
  EXPECT_NEAR(aligned->alignment.theta, inverse.theta, 1e-9);
}

TEST(AteTest, InterpolatesTruthBetweenPoses) {
  const std::vector<StampedPose> truth = {
      {0.0, Pose2(0, 0, 0)}, {0.2, Pose2(1, 0, 0.2)}, {5.0, Pose2(2, 0, 0)}};
  const std::vector<StampedPose> estimate = {
      {0.05, Pose2(0.45, 0, 0.05)},  // truth interpolated to (0.25, 0, 0.05): 0.2 m off
      {0.2005, Pose2(1, 0, 0.2)},    // nearest truth pose within 1 ms
      {2.0, Pose2(0, 0, 0)},         // inside a 4.8 s gap: unmatched
      {9.0, Pose2(0, 0, 0)}};        // after the truth ends: unmatched
  const Result<AteResult> result = EvaluateAte(estimate, truth);
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result->poses, 4u);
  EXPECT_EQ(result->matched, 2u);
  EXPECT_NEAR(result->ate_max_m, 0.2, 1e-12);
  EXPECT_NEAR(result->ate_rmse_m, std::sqrt(0.04 / 2), 1e-12);
  EXPECT_NEAR(result->rot_rmse_deg, 0.0, 1e-9);
}

TEST(AteTest, NoMatchIsAnError) {
  const Result<AteResult> result =
      EvaluateAte({{100.0, Pose2()}}, {{0.0, Pose2()}, {1.0, Pose2()}});
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.status().message(),
            "none of the 1 estimated poses has a truth pose at its time");
}

// The corrected Killian log stamps 1937 of its 1941 scans 4294967296 s: a time lookup would
// pair every estimate pose with one arbitrary truth pose and report nonsense, so it is refused.
TEST(AteTest, TruthPosesSharingATimestampCannotBePairedByTime) {
  const std::vector<StampedPose> truth = {
      {0.5, Pose2(0, 0, 0)}, {4294967296.0, Pose2(1, 0, 0)}, {4294967296.0, Pose2(2, 0, 0)}};
  const Result<AteResult> result = EvaluateAte(truth, truth);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.status().message().find("2 poses at time 4294967296"), std::string::npos)
      << result.status().message();
}

TEST(AteTest, PairingByIndexIgnoresTimestamps) {
  const std::vector<StampedPose> truth = {
      {0.0, Pose2(0, 0, 0)}, {0.0, Pose2(1, 0, 0)}, {0.0, Pose2(2, 0, 0.5)}, {0.0, Pose2(3, 1, 1)}};
  std::vector<StampedPose> estimate = truth;
  for (StampedPose& pose : estimate) pose.timestamp = 7.0;  // nothing to pair by time
  estimate[2].pose = Pose2(2.3, 0.4, 0.5);                  // 0.5 m off
  AteOptions options;
  options.pair_by_index = true;
  const Result<AteResult> result = EvaluateAte(estimate, truth, options);
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_EQ(result->matched, 4u);
  EXPECT_NEAR(result->ate_rmse_m, std::sqrt(0.25 / 4), 1e-12);
  EXPECT_NEAR(result->ate_max_m, 0.5, 1e-12);

  estimate.pop_back();
  const Result<AteResult> shorter = EvaluateAte(estimate, truth, options);
  ASSERT_FALSE(shorter.ok());
  EXPECT_NE(shorter.status().message().find("(3 vs 4)"), std::string::npos);
}

TEST(AteTest, JsonHasTheDesignKeysInOrder) {
  AteResult result;
  result.poses = 4;
  result.ate_rmse_m = 0.25;
  const nlohmann::ordered_json json = nlohmann::ordered_json::parse(AteResultToJson(result));
  std::vector<std::string> keys;
  for (const auto& item : json.items()) keys.push_back(item.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"poses", "matched", "ate_rmse_m", "ate_mean_m",
                                            "ate_max_m", "rot_rmse_deg"}));
  EXPECT_EQ(json["ate_rmse_m"], 0.25);
}

}  // namespace
}  // namespace semchain::eval
