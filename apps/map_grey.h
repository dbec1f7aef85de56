#pragma once

#include <opencv2/core.hpp>

#include "mapping/map_io.h"
#include "sim/world_drawing.h"

namespace semchain::app {

// The map as a grey image (CV_8UC1), top row first: free white, occupied black, unknown grey.
cv::Mat MapToGrey(const mapping::MapImage& map);

// An RGB colour as OpenCV's BGR scalar.
inline cv::Scalar Bgr(const sim::Color& c) { return {double(c[2]), double(c[1]), double(c[0])}; }

}  // namespace semchain::app
