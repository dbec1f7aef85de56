#include "mapping/pose_graph.h"

#include <gtest/gtest.h>

#include <random>

#include "core/angles.h"
#include "core/rng.h"
#include "mapping/testing/synthetic_world.h"

namespace semchain::mapping {
namespace {

// A 20 m × 20 m square driven twice, a node every metre.
std::vector<Pose2> SquareTruth() {
  std::vector<Pose2> truth;
  for (int lap = 0; lap < 2; ++lap) {
    for (int side = 0; side < 4; ++side) {
      const double heading = side * M_PI / 2.0;
      const Eigen::Vector2d corner[4] = {{0, 0}, {20, 0}, {20, 20}, {0, 20}};
      for (int k = 0; k < 20; ++k) {
        const Eigen::Vector2d at =
            corner[side] + k * Eigen::Vector2d(std::cos(heading), std::sin(heading));
        truth.emplace_back(at.x(), at.y(), NormalizeAngle(heading));
      }
    }
  }
  return truth;
}

// Odometry edges between consecutive nodes whose heading drifts by 0.2° a metre (a gyro bias,
// what loop closures exist to remove), and the initial poses they integrate to.
std::vector<PoseGraphEdge> DriftingOdometry(const std::vector<Pose2>& truth,
                                            std::vector<Pose2>* initial) {
  std::vector<PoseGraphEdge> edges;
  initial->assign(1, truth.front());
  Rng rng = MakeRng(5);
  std::normal_distribution<double> noise(0.0, 0.002);
  for (std::size_t i = 0; i + 1 < truth.size(); ++i) {
    const Pose2 step = truth[i].Between(truth[i + 1]);
    PoseGraphEdge edge;
    edge.from = static_cast<int>(i);
    edge.to = static_cast<int>(i + 1);
    // One draw a statement, θ first: argument order is unspecified (GCC's, last to first).
    const double theta = step.theta + DegToRad(0.2) + noise(rng);
    const double y = step.y + noise(rng), x = step.x + noise(rng);
    edge.relative = Pose2(x, y, theta);
    edge.sigmas = Eigen::Vector3d(0.05, 0.05, 0.02);
    edges.push_back(edge);
    initial->push_back(initial->back() * edge.relative);
  }
  return edges;
}

PoseGraphEdge Closure(const std::vector<Pose2>& truth, int from, int to, const Pose2& error = {}) {
  PoseGraphEdge edge;
  edge.from = from;
  edge.to = to;
  edge.relative =
      truth[static_cast<std::size_t>(from)].Between(truth[static_cast<std::size_t>(to)]) * error;
  edge.sigmas = Eigen::Vector3d(0.05, 0.05, 0.01);
  edge.loop_closure = true;
  return edge;
}

TEST(PoseGraphTest, WhitenedResidualOfAnAnalyticCase) {
  const std::vector<Pose2> poses = {Pose2(1.0, 2.0, M_PI / 2.0), Pose2(1.0, 4.0, M_PI)};
  PoseGraphEdge edge;
  edge.from = 0;
  edge.to = 1;
  // Node 1 is 2 m straight ahead of node 0, turned 90° left; measured 1.9 m, 0.1 m left, 80°.
  edge.relative = Pose2(1.9, 0.1, DegToRad(80.0));
  edge.sigmas = Eigen::Vector3d(0.1, 0.2, DegToRad(5.0));
  const Eigen::Vector3d r = WhitenedResidual(edge, poses);
  EXPECT_NEAR(r.x(), 1.0, 1e-9);
  EXPECT_NEAR(r.y(), -0.5, 1e-9);
  EXPECT_NEAR(r.z(), 2.0, 1e-9);
}

// A full covariance replaces the sigmas: with σ = 2 m along a direction at 45° in the frame of
// 'from' and 0.05 m across it, an error of 1 m along it whitens to 0.5 and 0.1 m across to 2.
TEST(PoseGraphTest, AFullCovarianceWhitensAlongItsAxes) {
  const std::vector<Pose2> poses = {Pose2(0.0, 0.0, 0.0), Pose2(3.0, 3.0, 0.0)};
  const Eigen::Vector2d along(std::sqrt(0.5), std::sqrt(0.5));
  const Eigen::Vector2d across(-along.y(), along.x());
  PoseGraphEdge edge;
  edge.from = 0;
  edge.to = 1;
  edge.covariance.topLeftCorner<2, 2>() =
      4.0 * along * along.transpose() + 0.0025 * across * across.transpose();
  edge.covariance(2, 2) = 1e-4;
  for (const auto& [offset, expected] :
       {std::pair{Eigen::Vector2d(along), 0.5}, std::pair{Eigen::Vector2d(0.1 * across), 2.0}}) {
    edge.relative = Pose2(3.0 - offset.x(), 3.0 - offset.y(), 0.0);
    EXPECT_NEAR(WhitenedResidual(edge, poses).norm(), expected, 1e-9);
  }
}

TEST(PoseGraphTest, LoopClosuresRemoveTheDrift) {
  const std::vector<Pose2> truth = SquareTruth();
  std::vector<Pose2> initial;
  std::vector<PoseGraphEdge> edges = DriftingOdometry(truth, &initial);
  ASSERT_GT(testing::MaxPositionError(initial, truth), 2.0);
  // The second lap sees the first: a closure every 10 nodes.
  for (int i = 80; i < 160; i += 10) edges.push_back(Closure(truth, i - 80, i));
  const PoseGraphSolution solution = OptimizePoseGraph(initial, edges);
  EXPECT_TRUE(solution.converged);
  EXPECT_LT(solution.final_cost, 0.01 * solution.initial_cost);
  EXPECT_LT(testing::MaxPositionError(solution.poses, truth), 0.3);
  // The first node is the frame.
  EXPECT_EQ(solution.poses.front().x, truth.front().x);
  EXPECT_EQ(solution.poses.front().theta, truth.front().theta);
}

// A closure that puts node 125 four metres beside where node 45 saw it (a look-alike
// corridor) and turned 20°, among eight right ones.
std::vector<PoseGraphEdge> EdgesWithAWrongClosure(const std::vector<Pose2>& truth,
                                                  std::vector<Pose2>* initial) {
  std::vector<PoseGraphEdge> edges = DriftingOdometry(truth, initial);
  for (int i = 80; i < 160; i += 10) edges.push_back(Closure(truth, i - 80, i));
  edges.push_back(Closure(truth, 45, 125, Pose2(0.0, 4.0, DegToRad(20.0))));
  return edges;
}

TEST(PoseGraphTest, TheRobustLossBoundsAWrongClosuresPull) {
  const std::vector<Pose2> truth = SquareTruth();
  std::vector<Pose2> initial;
  const std::vector<PoseGraphEdge> edges = EdgesWithAWrongClosure(truth, &initial);
  std::vector<PoseGraphEdge> right_only = edges;
  right_only.pop_back();
  const double right =
      testing::MaxPositionError(OptimizePoseGraph(initial, right_only).poses, truth);
  ASSERT_LT(right, 0.3);

  PoseGraphOptions squared;
  squared.loop_loss = RobustLoss::kNone;
  const double bent =
      testing::MaxPositionError(OptimizePoseGraph(initial, edges, squared).poses, truth);
  const PoseGraphSolution huber = OptimizePoseGraph(initial, edges);
  const double held = testing::MaxPositionError(huber.poses, truth);
  EXPECT_GT(bent, 1.0);
  EXPECT_LT(held, 0.5 * bent);
  // The wrong edge is left far from satisfied: its residual gives it away.
  EXPECT_GT(WhitenedResidual(edges.back(), huber.poses).norm(), 10.0);
}

TEST(PoseGraphTest, AContradictedClosureIsRejected) {
  const std::vector<Pose2> truth = SquareTruth();
  std::vector<Pose2> initial;
  const std::vector<PoseGraphEdge> edges = EdgesWithAWrongClosure(truth, &initial);
  const GatedPoseGraphSolution gated = OptimizeRejectingInconsistent(initial, edges, 5.0);
  ASSERT_EQ(gated.rejected.size(), 1u);
  EXPECT_EQ(gated.rejected.front(), static_cast<int>(edges.size()) - 1);
  EXPECT_LT(testing::MaxPositionError(gated.solution.poses, truth), 0.3);
  // With only right closures nothing is rejected.
  std::vector<PoseGraphEdge> right_only = edges;
  right_only.pop_back();
  EXPECT_TRUE(OptimizeRejectingInconsistent(initial, right_only, 5.0).rejected.empty());
}

}  // namespace
}  // namespace semchain::mapping
