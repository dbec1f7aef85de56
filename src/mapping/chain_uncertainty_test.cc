#include "mapping/chain_uncertainty.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/angles.h"
#include "core/rng.h"

namespace semchain::mapping {
namespace {

// A path that drives, turns and drives again, far from the origin (the prefix sums must not
// lose precision there): node poses and the steps between them.
std::vector<Pose2> WindingPath() {
  std::vector<Pose2> path{Pose2(250.0, -180.0, 0.3)};
  for (int k = 0; k < 60; ++k) {
    const double turn = (k % 15 == 14) ? 1.2 : 0.02;
    path.push_back(path.back() * Pose2(0.8, 0.0, turn));
  }
  return path;
}

constexpr double kSigmaMeters = 0.01;
constexpr double kSigmaRadians = 0.004;

// Perturbs every step of 'path' by N(0, σ²) in x and y (the step's frame) and heading, and
// returns the last node relative to node 'j' in node j's frame.
Pose2 PerturbedRelative(const std::vector<Pose2>& path, int j, Rng& rng) {
  std::normal_distribution<double> xy(0.0, kSigmaMeters);
  std::normal_distribution<double> th(0.0, kSigmaRadians);
  Pose2 relative;
  for (std::size_t k = static_cast<std::size_t>(j); k + 1 < path.size(); ++k) {
    Pose2 step = path[k].Between(path[k + 1]);
    // The heading error acts after the translation (it swings the nodes from k + 1 on); the
    // translation error is isotropic, so its frame does not matter.
    const double dx = xy(rng);
    const double dy = xy(rng);
    const double dth = th(rng);
    step.x += dx;
    step.y += dy;
    step.theta += dth;
    relative = relative * step;
  }
  return relative;
}

TEST(ChainUncertaintyTest, MatchesSampledChainsToFirstOrder) {
  const std::vector<Pose2> path = WindingPath();
  ChainUncertainty chain(path.front());
  for (std::size_t k = 1; k < path.size(); ++k) chain.Append(path[k], kSigmaMeters, kSigmaRadians);
  const int last = chain.size() - 1;
  for (const int j : {0, 20, 45}) {
    const Pose2 nominal = path[static_cast<std::size_t>(j)].Between(path.back());
    Rng rng = MakeRng(17);
    const int draws = 20000;
    Eigen::Matrix3d sampled = Eigen::Matrix3d::Zero();
    for (int d = 0; d < draws; ++d) {
      const Pose2 r = PerturbedRelative(path, j, rng);
      const Eigen::Vector3d e(r.x - nominal.x, r.y - nominal.y,
                              NormalizeAngle(r.theta - nominal.theta));
      sampled += e * e.transpose();
    }
    sampled /= draws;
    const Eigen::Matrix3d predicted = chain.Relative(j, last);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        // 20000 draws: a few per cent of sampling error on each entry's scale.
        const double scale = std::sqrt(predicted(r, r) * predicted(c, c));
        EXPECT_NEAR(sampled(r, c), predicted(r, c), 0.06 * scale)
            << "j " << j << " (" << r << ", " << c << ")";
      }
    }
  }
}

TEST(ChainUncertaintyTest, AStraightLineGrowsItsLateralSpreadWithTheCubeOfTheLength) {
  // Heading noise only: the lateral variance after n unit steps is q Σ_{m=0}^{n-1} m² =
  // q (n − 1) n (2n − 1) / 6 (each heading error swings the rest of the line).
  ChainUncertainty chain(Pose2(0.0, 0.0, kPi / 2));
  const int n = 30;
  for (int k = 1; k <= n; ++k) chain.Append(Pose2(0.0, k, kPi / 2), 0.0, 0.01);
  const Eigen::Matrix3d c = chain.Relative(0, n);
  const double q = 1e-4;
  EXPECT_NEAR(c(1, 1), q * (n - 1) * n * (2 * n - 1) / 6.0, 1e-9);  // lateral in the start frame
  EXPECT_NEAR(c(0, 0), 0.0, 1e-9);                                  // along the line
  EXPECT_NEAR(c(2, 2), q * n, 1e-12);
  // Sub-chains are differences: from node 10 the line is 20 long.
  const Eigen::Matrix3d tail = chain.Relative(10, n);
  EXPECT_NEAR(tail(1, 1), q * 19 * 20 * 39 / 6.0, 1e-9);
}

TEST(ChainUncertaintyTest, RepositioningMovesTheLeverArms) {
  ChainUncertainty chain{Pose2()};
  std::vector<Pose2> straight{Pose2()}, folded{Pose2()};
  for (int k = 1; k <= 10; ++k) {
    straight.emplace_back(k, 0.0, 0.0);
    folded.emplace_back(k <= 5 ? k : 10 - k, 0.0, 0.0);
    chain.Append(straight.back(), 0.0, 0.01);
  }
  const double lateral_straight = chain.Relative(0, 10)(1, 1);
  chain.Reposition(folded);  // the path comes back: node 10 is at the start
  EXPECT_LT(chain.Relative(0, 10)(1, 1), 0.5 * lateral_straight);
}

TEST(ChainUncertaintyTest, AnotherNodesFrameRotatesThePositionBlock) {
  const std::vector<Pose2> path = WindingPath();
  ChainUncertainty chain(path.front());
  for (std::size_t k = 1; k < path.size(); ++k) chain.Append(path[k], kSigmaMeters, kSigmaRadians);
  const int last = chain.size() - 1;
  const double turn = path[20].theta - path[5].theta;  // from node 20's frame into node 5's
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  rotation.topLeftCorner<2, 2>() << std::cos(turn), -std::sin(turn), std::sin(turn), std::cos(turn);
  const Eigen::Matrix3d expected = rotation * chain.Relative(20, last) * rotation.transpose();
  EXPECT_TRUE(chain.Relative(20, last, 5).isApprox(expected, 1e-12));
}

}  // namespace
}  // namespace semchain::mapping
