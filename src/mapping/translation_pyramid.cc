#include "mapping/translation_pyramid.h"

#include "core/check.h"

namespace semchain::mapping {

TranslationPyramid::TranslationPyramid(const std::vector<std::uint8_t>& allowed, int width,
                                       int height, int depth) {
  SEMCHAIN_CHECK(width > 0 && height > 0 && depth >= 0 && depth < 16);
  SEMCHAIN_CHECK(allowed.size() == static_cast<std::size_t>(width) * height);
  levels_.reserve(static_cast<std::size_t>(depth) + 1);
  levels_.push_back({0, width, height, allowed});
  for (int h = 1; h <= depth; ++h) {
    const Level& below = levels_.back();
    const int half = 1 << (h - 1);
    Level level;
    level.offset = (1 << h) - 1;
    level.width = width + level.offset;
    level.height = height + level.offset;
    level.any.assign(static_cast<std::size_t>(level.width) * level.height, 0);
    // Block (x, y) of size 2^h = blocks (x, y), (x + half, y), (x, y + half), (x + half,
    // y + half) of size 2^(h − 1).
    for (int py = 0; py < level.height; ++py) {
      const int y = py - level.offset;
      for (int px = 0; px < level.width; ++px) {
        const int x = px - level.offset;
        const bool any = Below(below, x, y) || Below(below, x + half, y) ||
                         Below(below, x, y + half) || Below(below, x + half, y + half);
        level.any[static_cast<std::size_t>(py) * level.width + px] = any ? 1 : 0;
      }
    }
    levels_.push_back(std::move(level));
  }
}

bool TranslationPyramid::Below(const Level& level, int x, int y) {
  const int px = x + level.offset;
  const int py = y + level.offset;
  if (px < 0 || py < 0 || px >= level.width || py >= level.height) return false;
  return level.any[static_cast<std::size_t>(py) * level.width + px] != 0;
}

}  // namespace semchain::mapping
