#include "apps/map_grey.h"

#include <cstdint>

namespace semchain::app {

cv::Mat MapToGrey(const mapping::MapImage& map) {
  cv::Mat grey(map.height, map.width, CV_8UC1);
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      const int value = map.At(x, y);
      grey.at<std::uint8_t>(map.height - 1 - y, x) =
          value < 0 ? 205 : static_cast<std::uint8_t>(254 - value * 254 / 100);
    }
  }
  return grey;
}

}  // namespace semchain::app
