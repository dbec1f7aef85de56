#pragma once

#include <memory>
#include <vector>

#include "core/pose2.h"
#include "mapping/occupancy_grid.h"

namespace semchain::mapping {

// One pose of a particle's trajectory. Particles descending from the same ancestor share the
// nodes up to it (a tree), so storing N trajectories costs what differs between them.
struct TrajectoryNode {
  Pose2 pose;
  int scan_index = -1;  // index of the scan in the run's scan sequence
  std::shared_ptr<const TrajectoryNode> parent;
};

// A sample of the RBPF: a pose hypothesis with its weight, its map and its path (seed 003 eq. 1
// factorisation: the map is conditioned on the particle's trajectory).
struct Particle {
  Pose2 pose;
  double log_weight = 0.0;  // accumulated since the last resampling
  // Accumulated over the whole run and inherited through resampling: picks the best particle.
  double cumulative_log_weight = 0.0;
  // Shared with other particles; written only when this particle holds the sole reference
  // (otherwise copied first, which is cheap: the grid itself shares its patches).
  std::shared_ptr<OccupancyGrid> map;
  std::shared_ptr<const TrajectoryNode> trajectory;  // newest node first
};

// The trajectory from the first node to 'last', oldest first.
inline std::vector<const TrajectoryNode*> Unroll(
    const std::shared_ptr<const TrajectoryNode>& last) {
  std::vector<const TrajectoryNode*> nodes;
  for (const TrajectoryNode* node = last.get(); node != nullptr; node = node->parent.get()) {
    nodes.push_back(node);
  }
  return {nodes.rbegin(), nodes.rend()};
}

}  // namespace semchain::mapping
