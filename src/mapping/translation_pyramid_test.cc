#include "mapping/translation_pyramid.h"

#include <gtest/gtest.h>

#include <random>

namespace semchain::mapping {
namespace {

// Every block of every level answers as a brute-force scan of the mask does, also blocks that
// start left of / below the map or run off it.
TEST(TranslationPyramidTest, BlocksAgreeWithBruteForce) {
  const int width = 23, height = 17, depth = 4;
  std::mt19937 rng(5);
  std::vector<std::uint8_t> allowed(static_cast<std::size_t>(width * height), 0);
  for (int k = 0; k < 12; ++k) {
    allowed[static_cast<std::size_t>(
        std::uniform_int_distribution<int>(0, width * height - 1)(rng))] = 1;
  }
  const TranslationPyramid pyramid(allowed, width, height, depth);
  ASSERT_EQ(pyramid.max_depth(), depth);
  for (int h = 0; h <= depth; ++h) {
    const int size = 1 << h;
    for (int y = -size - 1; y <= height + 1; ++y) {
      for (int x = -size - 1; x <= width + 1; ++x) {
        bool any = false;
        for (int j = y; j < y + size; ++j) {
          for (int i = x; i < x + size; ++i) {
            if (i >= 0 && j >= 0 && i < width && j < height &&
                allowed[static_cast<std::size_t>(j * width + i)] != 0) {
              any = true;
            }
          }
        }
        ASSERT_EQ(pyramid.Any(h, x, y), any) << "h " << h << " x " << x << " y " << y;
      }
    }
  }
}

}  // namespace
}  // namespace semchain::mapping
