#pragma once

#include <opencv2/core.hpp>

#include "mapping/map_io.h"

namespace semchain::app {

// The map as a grey image (CV_8UC1), top row first: free white, occupied black, unknown grey.
cv::Mat MapToGrey(const mapping::MapImage& map);

}  // namespace semchain::app
