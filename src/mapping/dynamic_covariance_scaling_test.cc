#include "mapping/dynamic_covariance_scaling.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/angles.h"
#include "mapping/pose_graph.h"
#include "mapping/testing/synthetic_world.h"

namespace semchain::mapping {
namespace {

TEST(DynamicCovarianceScalingTest, ScaleAndLossOfAgarwalEtAl) {
  const double phi = 2.0;
  // s = min(1, 2Φ / (Φ + χ²)): 1 up to Φ, 1/2 at 3Φ, 1/10 at 19Φ.
  EXPECT_DOUBLE_EQ(DcsScale(0.0, phi), 1.0);
  EXPECT_DOUBLE_EQ(DcsScale(phi, phi), 1.0);
  EXPECT_DOUBLE_EQ(DcsScale(3.0 * phi, phi), 0.5);
  EXPECT_DOUBLE_EQ(DcsScale(19.0 * phi, phi), 0.1);
  const DynamicCovarianceScalingLoss loss(phi);
  double rho[3];
  loss.Evaluate(1.5, rho);  // within Φ: squared
  EXPECT_DOUBLE_EQ(rho[0], 1.5);
  EXPECT_DOUBLE_EQ(rho[1], 1.0);
  EXPECT_DOUBLE_EQ(rho[2], 0.0);
  loss.Evaluate(3.0 * phi, rho);  // ρ = Φ (3χ² − Φ) / (Φ + χ²) = 2Φ, ρ' = s² = 1/4
  EXPECT_DOUBLE_EQ(rho[0], 2.0 * phi);
  EXPECT_DOUBLE_EQ(rho[1], 0.25);
  // ρ' is the derivative of ρ, and ρ'' that of ρ' (central differences).
  for (const double x : {phi + 0.5, 5.0 * phi, 40.0 * phi}) {
    const double h = 1e-5 * x;
    double below[3], above[3];
    loss.Evaluate(x, rho);
    loss.Evaluate(x - h, below);
    loss.Evaluate(x + h, above);
    EXPECT_NEAR(rho[1], (above[0] - below[0]) / (2.0 * h), 1e-6);
    EXPECT_NEAR(rho[2], (above[1] - below[1]) / (2.0 * h), 1e-6);
  }
  // Bounded by 3Φ: a closure however wrong adds at most that to the cost.
  loss.Evaluate(1e12, rho);
  EXPECT_NEAR(rho[0], 3.0 * phi, 1e-9);
}

// A 20 m × 20 m square driven twice, a node every metre.
std::vector<Pose2> SquareTruth() {
  std::vector<Pose2> truth;
  const Eigen::Vector2d corner[4] = {{0, 0}, {20, 0}, {20, 20}, {0, 20}};
  for (int lap = 0; lap < 2; ++lap) {
    for (int side = 0; side < 4; ++side) {
      const double heading = side * M_PI / 2.0;
      for (int k = 0; k < 20; ++k) {
        const Eigen::Vector2d at =
            corner[side] + k * Eigen::Vector2d(std::cos(heading), std::sin(heading));
        truth.emplace_back(at.x(), at.y(), NormalizeAngle(heading));
      }
    }
  }
  return truth;
}

PoseGraphEdge Edge(const std::vector<Pose2>& truth, int from, int to, bool loop_closure,
                   const Pose2& error = {}) {
  PoseGraphEdge edge;
  edge.from = from;
  edge.to = to;
  edge.relative =
      truth[static_cast<std::size_t>(from)].Between(truth[static_cast<std::size_t>(to)]) * error;
  edge.sigmas =
      loop_closure ? Eigen::Vector3d(0.05, 0.05, 0.01) : Eigen::Vector3d(0.05, 0.05, 0.02);
  edge.loop_closure = loop_closure;
  return edge;
}

// Exact odometry edges around the square twice, eight right closures from the second lap to the
// first, and four wrong ones (look-alike places metres away, one turned as well); the initial
// poses drift by 0.2° a metre of heading (what a filter hands the graph). The poses that satisfy
// every edge but the wrong ones are the truth.
struct Case {
  std::vector<Pose2> truth, initial;
  std::vector<PoseGraphEdge> edges;
  std::vector<std::size_t> right, wrong;  // indices of the closures in 'edges'
};

Case SquareWithWrongClosures() {
  Case c;
  c.truth = SquareTruth();
  c.initial.push_back(c.truth.front());
  for (std::size_t i = 0; i + 1 < c.truth.size(); ++i) {
    const int from = static_cast<int>(i);
    c.edges.push_back(Edge(c.truth, from, from + 1, false));
    const Pose2 drifted = c.edges.back().relative * Pose2(0.0, 0.0, DegToRad(0.2));
    c.initial.push_back(c.initial.back() * drifted);
  }
  for (int i = 80; i < 160; i += 10) {
    c.right.push_back(c.edges.size());
    c.edges.push_back(Edge(c.truth, i - 80, i, true));
  }
  const struct {
    int from, to;
    Pose2 error;
  } wrong[] = {{45, 125, Pose2(0.0, 4.0, DegToRad(20.0))},
               {12, 95, Pose2(3.0, 0.0, 0.0)},
               {25, 108, Pose2(-2.5, 0.5, DegToRad(5.0))},
               {63, 150, Pose2(0.0, -2.0, 0.0)}};
  for (const auto& w : wrong) {
    c.wrong.push_back(c.edges.size());
    c.edges.push_back(Edge(c.truth, w.from, w.to, true, w.error));
  }
  return c;
}

TEST(DynamicCovarianceScalingTest, WrongClosuresAreSwitchedOffAndTheGraphStaysRight) {
  const Case c = SquareWithWrongClosures();
  ASSERT_GT(testing::MaxPositionError(c.initial, c.truth), 2.0);
  PoseGraphOptions options;
  options.loop_loss = RobustLoss::kDynamicCovarianceScaling;
  const PoseGraphSolution solution = OptimizePoseGraph(c.initial, c.edges, options);
  EXPECT_LT(testing::MaxPositionError(solution.poses, c.truth), 0.03);
  ASSERT_EQ(solution.weights.size(), c.edges.size());
  for (const std::size_t e : c.wrong) EXPECT_LT(solution.weights[e], 0.1) << "edge " << e;
  for (const std::size_t e : c.right) EXPECT_GT(solution.weights[e], 0.9) << "edge " << e;
  EXPECT_EQ(solution.weights.front(), 1.0);  // a motion edge
}

TEST(DynamicCovarianceScalingTest, WithoutItTheWrongClosuresBendTheGraph) {
  const Case c = SquareWithWrongClosures();
  PoseGraphOptions squared;
  squared.loop_loss = RobustLoss::kNone;
  EXPECT_GT(
      testing::MaxPositionError(OptimizePoseGraph(c.initial, c.edges, squared).poses, c.truth),
      1.0);
  // Huber bounds each wrong closure's pull, but four of them still bend the graph by most of a
  // metre, and its weights do not tell the wrong closures from the right ones.
  PoseGraphOptions huber;
  huber.loop_loss = RobustLoss::kHuber;
  const PoseGraphSolution bent = OptimizePoseGraph(c.initial, c.edges, huber);
  EXPECT_GT(testing::MaxPositionError(bent.poses, c.truth), 0.5);
  for (const std::size_t e : c.wrong) EXPECT_GT(bent.weights[e], 0.1) << "edge " << e;
}

TEST(DynamicCovarianceScalingTest, TheSwitchedOffClosuresAreTheOnesRejected) {
  const Case c = SquareWithWrongClosures();
  PoseGraphOptions options;
  options.loop_loss = RobustLoss::kDynamicCovarianceScaling;
  const GatedPoseGraphSolution gated =
      OptimizeRejectingInconsistent(c.initial, c.edges, 5.0, options);
  std::vector<int> wrong(c.wrong.begin(), c.wrong.end());
  std::vector<int> rejected = gated.rejected;
  std::sort(rejected.begin(), rejected.end());
  EXPECT_EQ(rejected, wrong);
  EXPECT_LT(testing::MaxPositionError(gated.solution.poses, c.truth), 0.03);
}

}  // namespace
}  // namespace semchain::mapping
