#pragma once

#include <cstddef>
#include <vector>

#include "mapping/match_grid.h"

// The precomputation grids of branch-and-bound scan matching (Hess et al. 2016, §V.B;
// Cartographer's PrecomputationGridStack2D): grid h holds, for every cell (x, y), the largest M
// in the 2^h × 2^h block [x, x + 2^h) × [y, y + 2^h). Scoring a scan on grid h therefore bounds
// from above the score of every translation in that block: a node of the search tree at
// height h covers 2^h × 2^h finer candidates. Values are stored as bytes (M × 255, rounded), as
// Cartographer does, so that a large map's stack stays small and scoring is integer sums.
namespace semchain::mapping {

class PrecomputationGrid {
 public:
  // The grid of block width 'width' (a power of two) over 'grid'.
  PrecomputationGrid(const MatchGrid& grid, int width);

  // 255 × max of M over [x, x + w) × [y, y + w); the grid's outside value where the block
  // misses the map.
  int At(int x, int y) const {
    const int px = x + offset_;
    const int py = y + offset_;
    if (px < 0 || py < 0 || px >= width_ || py >= height_) return outside_;
    return values_[static_cast<std::size_t>(py * width_ + px)];
  }
  std::size_t bytes() const { return values_.size(); }

 private:
  int offset_;  // cell (x, y) is stored at (x + offset_, y + offset_): blocks may start left of 0
  int width_;
  int height_;
  unsigned char outside_ = 0;
  std::vector<unsigned char> values_;
};

// Grids of widths 1, 2, 4, …, 2^depth (index h = height in the search tree).
class PrecomputationGridStack {
 public:
  PrecomputationGridStack(const MatchGrid& grid, int depth);
  PrecomputationGridStack(const PrecomputationGridStack&) = delete;
  PrecomputationGridStack& operator=(const PrecomputationGridStack&) = delete;

  const PrecomputationGrid& Get(int height) const {
    return grids_[static_cast<std::size_t>(height)];
  }
  int max_depth() const { return static_cast<int>(grids_.size()) - 1; }
  std::size_t bytes() const;

 private:
  std::vector<PrecomputationGrid> grids_;
};

}  // namespace semchain::mapping
