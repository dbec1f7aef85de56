#pragma once

#include <cmath>
#include <opencv2/core.hpp>

#include "drawing/canvas.h"

// Colours and sub-pixel points as OpenCV's drawing calls take them.
namespace semchain::drawing {

constexpr int kShift = 4;  // OpenCV's fixed-point bits: sub-pixel accurate drawing

// An RGB colour as OpenCV's BGR scalar.
inline cv::Scalar Bgr(const Color& c) { return cv::Scalar(c[2], c[1], c[0]); }

// A sub-pixel point in the fixed-point form of OpenCV's calls with shift 'kShift'.
inline cv::Point Fixed(const cv::Point2d& p) {
  constexpr double kUnit = 1 << kShift;
  return cv::Point(static_cast<int>(std::lround(p.x * kUnit)),
                   static_cast<int>(std::lround(p.y * kUnit)));
}

}  // namespace semchain::drawing
