#include "eval/closure_metrics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/angles.h"

namespace semchain::eval {
namespace {

// A drive around a 10 m square, a scan every 0.5 m and 0.5 s (80 scans), the
// odometry exact but in its own frame (started elsewhere, turned).
struct Drive {
  std::vector<Pose2> truth;
  ScanTrack scans;
};

Drive SquareDrive() {
  Drive drive;
  const Pose2 odometry_frame(5.0, -3.0, 1.0);
  for (int side = 0; side < 4; ++side) {
    const double heading = side * M_PI / 2.0;
    const Eigen::Vector2d corner[4] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    for (int k = 0; k < 20; ++k) {
      const Eigen::Vector2d at =
          corner[side] + 0.5 * k * Eigen::Vector2d(std::cos(heading), std::sin(heading));
      drive.truth.emplace_back(at.x(), at.y(), NormalizeAngle(heading));
      drive.scans.timestamps.push_back(0.5 * static_cast<double>(drive.truth.size()));
      drive.scans.odometry.push_back(odometry_frame * drive.truth.back());
    }
  }
  return drive;
}

void ExpectPose(const std::optional<Pose2>& pose, const Pose2& expected) {
  ASSERT_TRUE(pose.has_value());
  EXPECT_NEAR(pose->x, expected.x, 1e-9);
  EXPECT_NEAR(pose->y, expected.y, 1e-9);
  EXPECT_NEAR(NormalizeAngle(pose->theta - expected.theta), 0.0, 1e-9);
}

TEST(ClosureReferenceTest, IndexedPoses) {
  const Drive drive = SquareDrive();
  const auto reference = MakeIndexedReference(drive.truth);
  ExpectPose(reference->Relative(3, 70), drive.truth[3].Between(drive.truth[70]));
  EXPECT_FALSE(reference->Relative(3, 80).has_value());
}

TEST(ClosureReferenceTest, TimedPosesBridgedByTheOdometry) {
  const Drive drive = SquareDrive();
  // Reference poses at every fourth scan (2 m apart), one at a time no scan has.
  std::vector<StampedPose> poses;
  for (std::size_t i = 0; i < drive.truth.size(); i += 4) {
    poses.push_back({drive.scans.timestamps[i], drive.truth[i]});
  }
  poses.push_back({1000.0, Pose2()});
  ClosureReferenceOptions options;
  options.max_bridge_meters = 1.0;
  const auto reference = MakeTimedReference(poses, drive.scans, options);
  // Scans 1 and 78: 0.5 m and 1 m from a reference pose.
  ExpectPose(reference->Relative(1, 78), drive.truth[1].Between(drive.truth[78]));
  ExpectPose(reference->Relative(0, 40), drive.truth[0].Between(drive.truth[40]));
  // Half a metre of bridge allowed: scan 78 is a metre from its nearest reference pose.
  options.max_bridge_meters = 0.5;
  EXPECT_FALSE(MakeTimedReference(poses, drive.scans, options)->Relative(1, 78).has_value());
  // Scan 19 is 1.5 m after the reference pose at scan 16 and half a metre before the one at
  // scan 20, which has turned the first corner: a quarter turn is too much turning to bridge.
  EXPECT_FALSE(MakeTimedReference(poses, drive.scans, options)->Relative(0, 19).has_value());
  options.max_bridge_radians = 2.0;
  ExpectPose(MakeTimedReference(poses, drive.scans, options)->Relative(0, 19),
             drive.truth[0].Between(drive.truth[19]));
}

TEST(ClosureReferenceTest, RelationsJoinedWithinTheErrorBudget) {
  const Drive drive = SquareDrive();
  const auto relation = [&drive](std::size_t a, std::size_t b) {
    return Relation{drive.scans.timestamps[a], drive.scans.timestamps[b],
                    drive.truth[a].Between(drive.truth[b])};
  };
  // Consecutive relations around the square every 2 scans, and one across it (scan 10 to 70).
  std::vector<Relation> relations;
  for (std::size_t i = 0; i + 2 < drive.truth.size(); i += 2)
    relations.push_back(relation(i, i + 2));
  relations.push_back(relation(10, 70));
  const auto reference = MakeRelationReference(relations, drive.scans);
  // Across the square through the one relation, bridged half a metre at each end.
  ExpectPose(reference->Relative(11, 69), drive.truth[11].Between(drive.truth[69]));
  ExpectPose(reference->Relative(10, 70), drive.truth[10].Between(drive.truth[70]));
  // Along the chain: a few relations are within the budget, thirty are not.
  ExpectPose(reference->Relative(20, 26), drive.truth[20].Between(drive.truth[26]));
  EXPECT_FALSE(reference->Relative(20, 50).has_value());
}

TEST(ClosureMetricsTest, LabelsByTheReferencesRelativePose) {
  const Drive drive = SquareDrive();
  const auto reference = MakeIndexedReference(drive.truth);
  mapping::LoopClosureCandidate candidate;
  candidate.from_scan = 5;
  candidate.to_scan = 65;
  const Pose2 truth = drive.truth[5].Between(drive.truth[65]);
  candidate.relative = truth * Pose2(0.2, 0.1, DegToRad(1.5));
  LabelledCandidate labelled = LabelCandidate(candidate, *reference);
  EXPECT_EQ(labelled.label, ClosureLabel::kTrue);
  EXPECT_NEAR(labelled.translation_error_m, std::hypot(0.2, 0.1), 1e-9);
  EXPECT_NEAR(labelled.rotation_error_rad, DegToRad(1.5), 1e-9);
  candidate.relative = truth * Pose2(0.0, 0.0, DegToRad(2.5));  // turned too far
  EXPECT_EQ(LabelCandidate(candidate, *reference).label, ClosureLabel::kFalse);
  candidate.relative = truth * Pose2(0.35, 0.0, 0.0);  // shifted too far
  EXPECT_EQ(LabelCandidate(candidate, *reference).label, ClosureLabel::kFalse);
  candidate.to_scan = 200;  // the reference has no such scan
  EXPECT_EQ(LabelCandidate(candidate, *reference).label, ClosureLabel::kUnlabelled);
}

LabelledCandidate Made(double score, ClosureLabel label, mapping::ClosureVerification v,
                       bool in_graph, double weight, int search = 0) {
  LabelledCandidate c;
  c.candidate.to = search;
  c.candidate.score = score;
  c.candidate.verification = v;
  c.candidate.in_graph = in_graph;
  c.candidate.weight = weight;
  c.label = label;
  return c;
}

TEST(ClosureMetricsTest, PrecisionAndRecallAtEachStage) {
  using V = mapping::ClosureVerification;
  const ClosureLabel t = ClosureLabel::kTrue, f = ClosureLabel::kFalse;
  // Searches from nodes 1 to 5; node 1 scored two true candidates (two submaps).
  const std::vector<LabelledCandidate> candidates = {
      Made(0.9, t, V::kAdded, true, 1.0, 1),        // kept
      Made(0.6, t, V::kNotReached, false, 0.0, 1),  // the other submap, lower
      Made(0.8, f, V::kAdded, true, 0.05, 2),       // switched off by the back end
      Made(0.8, t, V::kConfirmed, true, 0.9, 3),    // kept
      Made(0.7, f, V::kHeldBack, false, 0.0, 4),    // verification said no
      Made(0.7, t, V::kAdded, false, 0.0, 4),       // dropped by the back end
      Made(0.5, t, V::kNotReached, false, 0.0, 5),  // below the score gate
      Made(0.5, ClosureLabel::kUnlabelled, V::kNotReached, false, 0.0, 5)};
  const ClosureTable table = PrecisionRecall(candidates, {0.4, 0.75});
  EXPECT_EQ(table.candidates, 8);
  EXPECT_EQ(table.true_candidates, 5);
  EXPECT_EQ(table.true_searches, 4);
  EXPECT_EQ(table.false_candidates, 2);
  EXPECT_EQ(table.unlabelled, 1);
  const ThresholdRow& low = table.rows[0];
  EXPECT_EQ(low.scored.accepted, 8);
  EXPECT_EQ(low.scored.unlabelled_accepted, 1);
  EXPECT_DOUBLE_EQ(*low.scored.precision, 5.0 / 7.0);
  EXPECT_DOUBLE_EQ(*low.scored.recall, 1.0);
  EXPECT_DOUBLE_EQ(*low.scored.search_recall, 1.0);
  EXPECT_EQ(low.verified.accepted, 4);
  EXPECT_DOUBLE_EQ(*low.verified.precision, 3.0 / 4.0);
  EXPECT_DOUBLE_EQ(*low.verified.recall, 3.0 / 5.0);
  EXPECT_EQ(low.verified.true_searches_accepted, 3);  // nodes 1, 3, 4
  EXPECT_DOUBLE_EQ(*low.verified.search_recall, 3.0 / 4.0);
  EXPECT_EQ(low.back_end.accepted, 2);
  EXPECT_DOUBLE_EQ(*low.back_end.precision, 1.0);
  EXPECT_DOUBLE_EQ(*low.back_end.recall, 2.0 / 5.0);
  EXPECT_DOUBLE_EQ(*low.back_end.search_recall, 2.0 / 4.0);
  const ThresholdRow& high = table.rows[1];
  EXPECT_EQ(high.scored.accepted, 3);
  EXPECT_DOUBLE_EQ(*high.scored.precision, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(*high.scored.recall, 2.0 / 5.0);
  EXPECT_DOUBLE_EQ(*high.scored.search_recall, 2.0 / 4.0);
  // Nothing verified above 0.95: no precision.
  EXPECT_FALSE(PrecisionRecall(candidates, {0.95}).rows[0].verified.precision.has_value());
}

}  // namespace
}  // namespace semchain::eval
