#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "core/rng.h"

// Hand-made binary descriptors for the bag-of-words tests.
namespace semchain::bow::testing {

// A 32-byte descriptor filled with 'byte'.
inline cv::Mat Filled(unsigned char byte) { return cv::Mat(1, 32, CV_8UC1, cv::Scalar(byte)); }

// The rows stacked into one descriptor matrix.
inline cv::Mat Stack(const std::vector<cv::Mat>& rows) {
  cv::Mat all;
  for (const cv::Mat& row : rows) all.push_back(row);
  return all;
}

// 'count' seeded random descriptors.
inline cv::Mat RandomDescriptors(int count, std::uint64_t seed) {
  cv::Mat d(count, 32, CV_8UC1);
  Rng rng = MakeRng(seed);
  for (int r = 0; r < count; ++r) {
    for (int c = 0; c < 32; ++c) d.at<unsigned char>(r, c) = static_cast<unsigned char>(rng());
  }
  return d;
}

}  // namespace semchain::bow::testing
