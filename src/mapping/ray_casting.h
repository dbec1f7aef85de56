#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "core/pose2.h"
#include "mapping/occupancy_grid.h"
#include "mapping/prepared_scan.h"

namespace semchain::mapping {

// Appends to 'cells' the cells that the segment from 'start' to 'end' (grid coordinates: cell
// (i, j) spans [i, i+1) × [j, j+1)) passes through, in order from the start cell, excluding
// the cell that contains 'end' (Amanatides & Woo traversal: every cell the segment touches,
// 4-connected).
void TraceSegmentCells(const Eigen::Vector2d& start, const Eigen::Vector2d& end,
                       std::vector<Eigen::Vector2i>* cells);

// Integrates scans into occupancy grids. Each cell is updated at most once per scan (an update
// marker over the scan's bounding box), and a hit wins over a pass-through, so grazing beams do
// not erase the walls they run along. Keeps scratch memory: use one per thread.
class ScanInserter {
 public:
  // Integrates 'scan' taken at robot pose 'pose' into 'grid': a miss for each cell a beam
  // crosses, a hit for the cell a return ends in.
  void Insert(const PreparedScan& scan, const Pose2& pose, OccupancyGrid* grid);

 private:
  // True the first time 'cell' is seen in the current scan.
  bool Mark(const Eigen::Vector2i& cell);

  std::vector<std::uint32_t> stamps_;
  std::uint32_t generation_ = 0;
  Eigen::Vector2i box_min_{0, 0};
  int box_width_ = 0;
  std::vector<Eigen::Vector2i> ray_;
};

// Inserts with a per-thread ScanInserter.
void InsertScan(const PreparedScan& scan, const Pose2& pose, OccupancyGrid* grid);

}  // namespace semchain::mapping
