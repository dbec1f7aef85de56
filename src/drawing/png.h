#pragma once

#include <filesystem>
#include <opencv2/core.hpp>

#include "core/status.h"

namespace semchain::drawing {

// Writes 'bgr' as a PNG, atomically.
Status WritePng(const cv::Mat& bgr, const std::filesystem::path& path);

}  // namespace semchain::drawing
