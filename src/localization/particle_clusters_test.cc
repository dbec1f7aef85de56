#include "localization/particle_clusters.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace semchain::localization
