#include "mapping/loop_closure_geometry.h"

#include <gtest/gtest.h>

#include <vector>

namespace semchain::mapping::internal {
namespace {

PoseGraphEdge StepOfOneMeter(const LoopClosureOptions& options) {
  return MotionEdge(0, Pose2(0.0, 0.0, 0.0), Pose2(1.0, 0.0, 0.1), options);
}

TEST(LoosenSnapTest, AStepTheLocalEstimateAgreesWithKeepsTheModelsNoise) {
  const LoopClosureOptions options;
  PoseGraphEdge edge = StepOfOneMeter(options);
  const Eigen::Vector3d model = edge.sigmas;
  // 0.05 m and 0.01 rad off: within 10 σ of the model (0.04 m, 0.007 rad).
  EXPECT_FALSE(LoosenSnap(Pose2(1.05, 0.0, 0.11), options, &edge));
  EXPECT_EQ(edge.sigmas, model);
}

TEST(LoosenSnapTest, ASnapIsAsUncertainAsTheDisagreement) {
  LoopClosureOptions options;
  PoseGraphEdge edge = StepOfOneMeter(options);
  const Eigen::Vector3d model = edge.sigmas;
  // The local estimate turned 0.3 rad less and went 0.1 m to the side.
  ASSERT_TRUE(LoosenSnap(Pose2(1.0, -0.1, -0.2), options, &edge));
  EXPECT_NEAR(edge.sigmas.x(), 0.1, 1e-12);
  EXPECT_NEAR(edge.sigmas.y(), 0.1, 1e-12);
  EXPECT_NEAR(edge.sigmas.z(), 0.3, 1e-12);
  EXPECT_NEAR(edge.relative.theta, 0.1, 1e-12);  // the filter's step stays the mean
  options.snap_sigmas = 0.0;
  PoseGraphEdge off = StepOfOneMeter(options);
  EXPECT_FALSE(LoosenSnap(Pose2(1.0, -0.1, -0.2), options, &off));
  EXPECT_EQ(off.sigmas, model);
}

TEST(LoosenSnapTest, TheMotionNoiseScaleLeavesLoosenedEdgesAlone) {
  const LoopClosureOptions options;
  std::vector<PoseGraphEdge> edges = {StepOfOneMeter(options), StepOfOneMeter(options)};
  edges[1].from = 1;
  edges[1].to = 2;
  ASSERT_TRUE(LoosenSnap(Pose2(1.0, 0.0, -0.2), options, &edges[1]));
  const std::vector<PoseGraphEdge> scaled = ScaledMotion(edges, 0.01, {false, true});
  EXPECT_NEAR(scaled[0].sigmas.z(), 0.1 * edges[0].sigmas.z(), 1e-12);
  EXPECT_EQ(scaled[1].sigmas, edges[1].sigmas);
}

}  // namespace
}  // namespace semchain::mapping::internal
