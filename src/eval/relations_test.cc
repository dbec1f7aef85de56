#include "eval/relations.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/angles.h"
#include "io/carmen.h"

namespace semchain::eval {
namespace {

const std::filesystem::path kData = SEMCHAIN_SHARED_DATA_DIR;

std::filesystem::path WriteText(const std::string& name, const std::string& text) {
  const std::filesystem::path path = std::filesystem::path(testing::TempDir()) / name;
  std::ofstream(path) << text;
  return path;
}

// A three-pose trajectory along x and the relations between its consecutive poses.
std::vector<StampedPose> Straight() {
  return {{10.0, Pose2(0, 0, 0)}, {11.0, Pose2(1, 0, 0)}, {12.0, Pose2(2, 0, 0)}};
}

std::vector<Relation> RelationsOf(const std::vector<StampedPose>& poses) {
  std::vector<Relation> relations;
  for (std::size_t i = 0; i + 1 < poses.size(); ++i) {
    relations.push_back(
        {poses[i].timestamp, poses[i + 1].timestamp, poses[i].pose.Between(poses[i + 1].pose)});
  }
  return relations;
}

TEST(RelationsTest, ReadsRelationFiles) {
  const std::filesystem::path path =
      WriteText("r.relations",
                "# t1 t2 dx dy dz roll pitch dyaw\n\n"
                "1134864645.90321 1134864646.32420 0.31293 0.02935 0.00000  0.00000 0 0.24198\n");
  const Result<std::vector<Relation>> relations = ReadRelations(path);
  ASSERT_TRUE(relations.ok()) << relations.status().message();
  ASSERT_EQ(relations->size(), 1u);
  EXPECT_EQ((*relations)[0].t1, 1134864645.90321);
  EXPECT_EQ((*relations)[0].t2, 1134864646.32420);
  EXPECT_EQ((*relations)[0].delta.x, 0.31293);
  EXPECT_EQ((*relations)[0].delta.theta, 0.24198);
  const std::filesystem::path bad = WriteText("bad.relations", "1 2 3 4 5 6 7 8\n1 2 3 4 5 6 7\n");
  EXPECT_EQ(ReadRelations(bad).status().message(),
            bad.string() + ":2: truncated line: missing dyaw");
  const std::filesystem::path nan = WriteText("nan.relations", "1 2 nan 4 5 6 7 8\n");
  EXPECT_EQ(ReadRelations(nan).status().message(), nan.string() + ":1: dx: 'nan' is not finite");
  EXPECT_FALSE(ReadRelations(bad.string() + ".missing").ok());
}

TEST(RelationsTest, TrajectoryAgainstItsOwnRelationsScoresZero) {
  const std::vector<StampedPose> poses = {
      {0.0, Pose2(0, 0, 0)}, {0.5, Pose2(1, 2, 3)}, {1.0, Pose2(-4, 1, -2)}, {2.0, Pose2(3, 3, 1)}};
  const Result<RelationErrors> errors = EvaluateRelations(poses, RelationsOf(poses));
  ASSERT_TRUE(errors.ok());
  EXPECT_EQ(errors->relations, 3u);
  EXPECT_EQ(errors->matched, 3u);
  EXPECT_NEAR(errors->trans_mean_m, 0.0, 1e-12);
  EXPECT_NEAR(errors->rot_mean_deg, 0.0, 1e-12);
  EXPECT_NEAR(errors->rot_sq_std, 0.0, 1e-12);
}

TEST(RelationsTest, RotatedMiddlePoseGivesHandComputedErrors) {
  std::vector<Relation> relations = RelationsOf(Straight());
  relations.push_back({10.0, 99.0, Pose2(1, 0, 0)});  // t2 is not in the trajectory
  std::vector<StampedPose> estimate = Straight();
  estimate[1].pose = Pose2(1, 0, 0.1);
  estimate[2].timestamp += 4e-4;  // within the 1 ms tolerance
  // δ*_01 = (1, 0, 0.1): no translational error, 0.1 rad. δ*_12 = (cos 0.1, -sin 0.1, -0.1):
  // translational error |(cos 0.1 - 1, -sin 0.1)| = 2 sin 0.05, again 0.1 rad.
  const Result<RelationErrors> errors = EvaluateRelations(estimate, relations);
  ASSERT_TRUE(errors.ok());
  const double e = 2.0 * std::sin(0.05);
  const double rot = RadToDeg(0.1);
  EXPECT_EQ(errors->relations, 3u);
  EXPECT_EQ(errors->matched, 2u);
  EXPECT_NEAR(errors->trans_mean_m, e / 2, 1e-12);
  EXPECT_NEAR(errors->trans_std_m, e / 2, 1e-12);
  EXPECT_NEAR(errors->rot_mean_deg, rot, 1e-9);
  EXPECT_NEAR(errors->rot_std_deg, 0.0, 1e-9);
  EXPECT_NEAR(errors->trans_sq_mean, e * e / 2, 1e-12);
  EXPECT_NEAR(errors->trans_sq_std, e * e / 2, 1e-12);
  EXPECT_NEAR(errors->rot_sq_mean, rot * rot, 1e-9);
  EXPECT_NEAR(errors->rot_sq_std, 0.0, 1e-9);
}

TEST(RelationsTest, RotationErrorWrapsAroundPi) {
  const Relation relation{0, 1, Pose2(0, 0, 3.1)};
  const RelationError error = ErrorOfRelation(relation, Pose2(0, 0, 0), Pose2(0, 0, -3.1));
  EXPECT_NEAR(error.rot_rad, 2 * kPi - 6.2, 1e-12);
}

TEST(RelationsTest, NoMatchIsAnError) {
  const Result<RelationErrors> errors =
      EvaluateRelations(Straight(), {{50.0, 51.0, Pose2(1, 0, 0)}});
  ASSERT_FALSE(errors.ok());
  EXPECT_EQ(errors.status().message(),
            "none of the 1 relations has both timestamps in the trajectory (within 0.001 s)");
}

TEST(RelationsTest, JsonHasTheDesignKeysInOrder) {
  RelationErrors errors;
  errors.relations = 3;
  errors.matched = 2;
  errors.trans_mean_m = 0.5;
  const nlohmann::ordered_json json = nlohmann::ordered_json::parse(RelationErrorsToJson(errors));
  std::vector<std::string> keys;
  for (const auto& item : json.items()) keys.push_back(item.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"relations", "matched", "trans_mean_m", "trans_std_m",
                                            "rot_mean_deg", "rot_std_deg", "trans_sq_mean",
                                            "trans_sq_std", "rot_sq_mean", "rot_sq_std"}));
  EXPECT_EQ(json["matched"], 2);
  EXPECT_EQ(json["trans_mean_m"], 0.5);
}

// The raw MIT CSAIL odometry (the pose fields of its FLASER lines) scored with the published
// relations: every relation matches a scan, and odometry alone is far from the SLAM results
// (GMapping 0.049 m, graph mapping 0.004 m in Kümmerle et al. 2009). The 1040 relations between
// scans less than a second apart have small errors (median below 1 mm), but the loop-closing
// ones span up to 233 s of drift, so the mean is 1.68 m (std 5.29 m) and 5.07° (std 8.24°);
// these values were checked with an independent script.
TEST(RelationsTest, RawMitCsailOdometry) {
  const Result<carmen::Log> log = carmen::ReadLog(kData / "mit-csail" / "mit-csail.clf");
  ASSERT_TRUE(log.ok()) << log.status().message();
  std::vector<StampedPose> odometry;
  for (const carmen::Laser* laser : log->Lasers()) {
    odometry.push_back({laser->stamp.timestamp, laser->scan.odometry});
  }
  const Result<std::vector<Relation>> relations =
      ReadRelations(kData / "mit-csail" / "mit-csail.relations");
  ASSERT_TRUE(relations.ok()) << relations.status().message();
  const Result<RelationErrors> errors = EvaluateRelations(odometry, *relations);
  ASSERT_TRUE(errors.ok()) << errors.status().message();
  EXPECT_EQ(errors->relations, 1172u);
  EXPECT_EQ(errors->matched, 1172u);
  EXPECT_GT(errors->trans_mean_m, 1.0);  // odometry is no SLAM result
  EXPECT_NEAR(errors->trans_mean_m, 1.6815, 1e-3);
  EXPECT_NEAR(errors->trans_std_m, 5.2922, 1e-3);
  EXPECT_NEAR(errors->rot_mean_deg, 5.0718, 1e-3);
  EXPECT_NEAR(errors->rot_std_deg, 8.2411, 1e-3);
}

}  // namespace
}  // namespace semchain::eval
