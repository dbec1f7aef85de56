#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/pose2.h"

// Particle clusters as nav2's pf_cluster_stats forms them: particles are binned on an
// (x, y, θ) histogram, bins that touch (26-neighbourhood) form a cluster, and each cluster
// gets its weight, weighted mean (circular mean for θ) and covariance. AMCL's estimate is the
// mean of the heaviest cluster. Heading bins wrap around: nav2 keeps particle headings unwrapped,
// so a cloud it tracks through ±π stays one cluster; with headings kept in (−π, π] the bins on
// either side of ±π must touch for the same result.
namespace semchain::localization {

struct Particle {
  Pose2 pose;
  double weight = 0.0;
};

struct PoseCluster {
  double weight = 0.0;  // sum of its particles' (normalised) weights
  int count = 0;
  Pose2 mean;
  // x–y block from weighted second moments; θ variance −2 ln R̄ (circular), θ uncorrelated.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

// Clusters of 'particles' on bins of 'bin_size' (x, y, θ; θ bins counted from −π), heaviest
// first.
std::vector<PoseCluster> ClusterParticles(const std::vector<Particle>& particles,
                                          const Eigen::Vector3d& bin_size);

}  // namespace semchain::localization
