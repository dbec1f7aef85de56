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
  // max over [x, x + w) × [y, y + w). Padding with the grid's outside value on every side lets
  // blocks start at -(w - 1) and reach past the end; the first width_ × height_ block starts
  // are kept.
  const cv::Mat probabilities(grid.height, grid.width, CV_32F,
                              const_cast<float*>(grid.values.data()));
  cv::Mat source;
  probabilities.convertTo(source, CV_8U, 255.0);  // rounds and saturates
  outside_ = cv::saturate_cast<unsigned char>(255.0 * grid.outside);
  cv::Mat padded;
  cv::copyMakeBorder(source, padded, offset_, offset_, offset_, offset_, cv::BORDER_CONSTANT,
                     cv::Scalar(outside_));
  cv::Mat filtered;
  if (width == 1) {
    filtered = padded;
  } else {
    cv::dilate(padded, filtered, cv::Mat::ones(width, width, CV_8U), cv::Point(0, 0));
  }
  const cv::Mat kept = filtered(cv::Rect(0, 0, width_, height_)).clone();
  values_.assign(kept.begin<unsigned char>(), kept.end<unsigned char>());
}

PrecomputationGridStack::PrecomputationGridStack(const MatchGrid& grid, int depth) {
  SEMCHAIN_CHECK(depth >= 0 && depth < 16);
  grids_.reserve(static_cast<std::size_t>(depth) + 1);
  for (int h = 0; h <= depth; ++h) grids_.emplace_back(grid, 1 << h);
}

std::size_t PrecomputationGridStack::bytes() const {
  std::size_t sum = 0;
  for (const PrecomputationGrid& grid : grids_) sum += grid.bytes();
  return sum;
}

}  // namespace semchain::mapping
