#include "localization/particle_clusters.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/angles.h"

namespace semchain::localization {
namespace {

TEST(ParticleClustersTest, TouchingBinsFormOneClusterHeaviestFirst) {
  std::vector<Particle> particles;
  // Cluster A around (1, 1, 0): weights 0.1 each, spread over touching bins.
  for (const double dx : {-0.3, 0.0, 0.3}) particles.push_back({Pose2(1.0 + dx, 1.0, 0.0), 0.1});
  // Cluster B around (5, 5, π): weight 0.35 each, headings either side of ±π.
  particles.push_back({Pose2(5.0, 5.0, 3.1), 0.35});
  particles.push_back({Pose2(5.1, 5.0, 3.1), 0.35});
  const std::vector<PoseCluster> clusters = ClusterParticles(particles, {0.5, 0.5, 0.17});
  ASSERT_EQ(clusters.size(), 2u);
  EXPECT_NEAR(clusters[0].weight, 0.7, 1e-12);
  EXPECT_EQ(clusters[0].count, 2);
  EXPECT_NEAR(clusters[0].mean.x, 5.05, 1e-12);
  EXPECT_NEAR(clusters[0].mean.theta, 3.1, 1e-12);
  EXPECT_NEAR(clusters[0].covariance(0, 0), 0.0025, 1e-12);
  EXPECT_NEAR(clusters[1].weight, 0.3, 1e-12);
  EXPECT_NEAR(clusters[1].mean.x, 1.0, 1e-12);
  EXPECT_NEAR(clusters[1].covariance(0, 0), 0.06, 1e-12);
  EXPECT_NEAR(clusters[1].covariance(2, 2), 0.0, 1e-12);
}

// nav2 never wraps a particle's heading, so a cloud it tracks through ±π stays one cluster; with
// headings in (−π, π] the heading bins must wrap for the same answer.
TEST(ParticleClustersTest, HeadingBinsWrapAroundPlusMinusPi) {
  std::vector<Particle> particles;
  for (const double theta : {kPi - 0.05, kPi - 0.01, -kPi + 0.01, -kPi + 0.05}) {
    particles.push_back({Pose2(2.0, 3.0, theta), 0.2});
  }
  particles.push_back({Pose2(2.1, 3.0, 0.0), 0.2});  // same place, facing the other way
  const std::vector<PoseCluster> clusters = ClusterParticles(particles, {0.5, 0.5, DegToRad(10.0)});
  ASSERT_EQ(clusters.size(), 2u);
  EXPECT_EQ(clusters[0].count, 4);
  EXPECT_NEAR(clusters[0].weight, 0.8, 1e-12);
  EXPECT_NEAR(std::abs(clusters[0].mean.theta), kPi, 1e-12);  // circular mean: the symmetric ±π
  EXPECT_EQ(clusters[1].count, 1);
}

// Bins that do not divide the circle: the last, narrower bin still touches the first.
TEST(ParticleClustersTest, UnevenHeadingBinsStillWrap) {
  const std::vector<Particle> particles = {{Pose2(0.1, 0.1, 3.13), 0.5},
                                           {Pose2(0.1, 0.1, -3.13), 0.5}};
  EXPECT_EQ(ClusterParticles(particles, {0.5, 0.5, 0.4}).size(), 1u);   // 16 bins, last 0.28 rad
  EXPECT_EQ(ClusterParticles(particles, {0.5, 0.5, 0.05}).size(), 1u);  // 126 bins, last 0.03 rad
}

}  // namespace
}  // namespace semchain::localization
