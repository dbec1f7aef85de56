#include "eval/map_frame.h"

#include <gtest/gtest.h>

namespace semchain::eval {
namespace {

std::vector<StampedPose> Straight(int poses, double step) {
  std::vector<StampedPose> path;
  for (int i = 0; i < poses; ++i) path.push_back({0.1 * i, Pose2(step * i, 0.0, 0.0)});
  return path;
}

void ExpectPoseNear(const Pose2& actual, const Pose2& expected) {
  EXPECT_NEAR(actual.x, expected.x, 1e-9);
  EXPECT_NEAR(actual.y, expected.y, 1e-9);
  EXPECT_NEAR(actual.theta, expected.theta, 1e-9);
}

// A map built from a trajectory that is off the truth by one rigid transform shows every place
// moved by it.
TEST(MapFrameTest, AMapOffByOneTransformMovesEveryPlaceByIt) {
  const std::vector<StampedPose> truth = Straight(20, 0.5);
  const Pose2 offset(0.1, -0.05, 0.02);
  std::vector<StampedPose> estimate = truth;
  for (StampedPose& pose : estimate) pose.pose = offset * pose.pose;
  const Result<MapFrame> frame = MapFrame::FromTrajectories(estimate, truth);
  ASSERT_TRUE(frame.ok()) << frame.status().message();
  const Pose2 robot(3.2, 1.5, 0.7);
  ExpectPoseNear(frame->FromWorld(robot), offset * robot);
}

// A corridor whose far half the SLAM bent sideways: a place there takes the far half's
// correction, a place near the start the start's.
TEST(MapFrameTest, EachPlaceTakesTheCorrectionOfTheNearestMappingPose) {
  const std::vector<StampedPose> truth = Straight(40, 1.0);
  std::vector<StampedPose> estimate = truth;
  for (std::size_t i = 20; i < estimate.size(); ++i) estimate[i].pose.y += 0.1;
  // Timestamps pair the poses, whatever their order.
  std::reverse(estimate.begin(), estimate.end());
  const Result<MapFrame> frame = MapFrame::FromTrajectories(estimate, truth);
  ASSERT_TRUE(frame.ok()) << frame.status().message();
  ExpectPoseNear(frame->FromWorld(Pose2(2.2, 1.0, 0.3)), Pose2(2.2, 1.0, 0.3));
  ExpectPoseNear(frame->FromWorld(Pose2(30.4, -1.0, 0.3)), Pose2(30.4, -0.9, 0.3));
}

TEST(MapFrameTest, TrajectoriesWhoseTimestampsDoNotPairAreAnError) {
  std::vector<StampedPose> estimate = Straight(5, 1.0);
  for (StampedPose& pose : estimate) pose.timestamp += 100.0;
  EXPECT_FALSE(MapFrame::FromTrajectories(estimate, Straight(5, 1.0)).ok());
  EXPECT_FALSE(MapFrame::FromTrajectories({}, Straight(5, 1.0)).ok());
}

}  // namespace
}  // namespace semchain::eval
