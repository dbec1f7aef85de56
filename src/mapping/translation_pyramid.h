#pragma once

#include <cstdint>
#include <vector>

// Where a global branch-and-bound search may place the robot: a mask of allowed cells (e.g. the
// map's free space, dilated a little) and, per tree height h, whether a 2^h × 2^h block of
// translations [x, x + 2^h) × [y, y + 2^h) holds any allowed cell, so that a search node whose
// translations all lie in walls or unknown space is dropped before it is scored. Built level by
// level (a block is four blocks of the level below), linear in the cells per level.
namespace semchain::mapping {

class TranslationPyramid {
 public:
  // 'allowed': width × height, row-major (row 0 at the map's origin), non-zero = allowed.
  TranslationPyramid(const std::vector<std::uint8_t>& allowed, int width, int height, int depth);

  // Whether block [x, x + 2^h) × [y, y + 2^h) (cells, may extend off the map) holds an allowed
  // cell; false for blocks entirely off the map.
  bool Any(int h, int x, int y) const { return Below(levels_[static_cast<std::size_t>(h)], x, y); }
  int max_depth() const { return static_cast<int>(levels_.size()) - 1; }

 private:
  // Level h stores block (x, y) at (x + offset, y + offset), offset = 2^h − 1: blocks may start
  // left of and below cell 0.
  struct Level {
    int offset = 0;
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> any;
  };
  static bool Below(const Level& level, int x, int y);

  std::vector<Level> levels_;
};

}  // namespace semchain::mapping
