#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>

#include "mapping/map_io.h"

// Where on an occupancy map a robot may stand, for pre-localization's hypotheses: free space
// clear of anything occupied, or a cell the mapping run never saw close to the free space.
namespace semchain::localization {

class StandableSpace {
 public:
  // 'clearance': metres a free point must keep from anything occupied; 'unknown_reach': metres
  // from the free space within which an unseen cell is standable (0: free space only).
  StandableSpace(const mapping::MapImage& occupancy, double clearance, double unknown_reach);

  // Whether 'point' lies in free space at least 'clearance' from anything occupied.
  bool InFreeSpace(const Eigen::Vector2d& point) const;
  // Whether 'point' lies in the map on a cell not occupied (free or unknown).
  bool OffObstacles(const Eigen::Vector2d& point) const;
  // Whether a robot may stand at 'point': InFreeSpace, or an unknown cell within unknown_reach of
  // the free space.
  bool Standable(const Eigen::Vector2d& point) const;

 private:
  // The occupancy map's cell holding 'point' (x, y), when the map covers it.
  std::optional<Eigen::Vector2i> MapCell(const Eigen::Vector2d& point) const;

  mapping::MapImage occupancy_;
  double clearance_meters_;
  double unknown_reach_;
  cv::Mat clearance_;  // CV_32F metres to the nearest non-free cell (0 on it), row = cell y
  cv::Mat to_free_;    // CV_32F metres to the nearest free cell (0 on it), row = cell y
};

}  // namespace semchain::localization
