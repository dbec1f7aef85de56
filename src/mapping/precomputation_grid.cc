#include "mapping/precomputation_grid.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/check.h"

namespace semchain::mapping {

PrecomputationGrid::PrecomputationGrid(const MatchGrid& grid, int width)
    : offset_(width - 1), width_(grid.width + width - 1), height_(grid.height + width - 1) {
  SEMCHAIN_CHECK(width >= 1 && (width & (width - 1)) == 0);
  SEMCHAIN_CHECK(grid.width > 0 && grid.height > 0);
  // A max filter is a dilation: with the kernel's anchor at its corner, dilate gives
  // max over [x, x + w) × [y, y + w). Zero padding in front lets blocks start at -(w - 1);
  // pixels past the end are ignored by dilate (M >= 0, so this equals zero padding).
  const cv::Mat probabilities(grid.height, grid.width, CV_32F,
                              const_cast<float*>(grid.values.data()));
  cv::Mat source;
  probabilities.convertTo(source, CV_8U, 255.0);  // rounds and saturates
  cv::Mat padded;
  cv::copyMakeBorder(source, padded, offset_, 0, offset_, 0, cv::BORDER_CONSTANT, cv::Scalar(0));
  cv::Mat filtered;
  if (width == 1) {
    filtered = padded;
  } else {
    cv::dilate(padded, filtered, cv::Mat::ones(width, width, CV_8U), cv::Point(0, 0));
  }
  values_.assign(filtered.begin<unsigned char>(), filtered.end<unsigned char>());
}

PrecomputationGridStack::PrecomputationGridStack(const MatchGrid& grid, int depth) {
  SEMCHAIN_CHECK(depth >= 0 && depth < 16);
  grids_.reserve(static_cast<std::size_t>(depth) + 1);
  for (int h = 0; h <= depth; ++h) grids_.emplace_back(grid, 1 << h);
}

}  // namespace semchain::mapping
