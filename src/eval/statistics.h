#pragma once

#include <cmath>
#include <vector>

namespace semchain::eval {

struct MeanStd {
  double mean = 0.0;
  double std = 0.0;  // population standard deviation (divides by n), 0 for n <= 1
};

// Mean and standard deviation of 'values' (both 0 when empty). Two passes, so that values with
// a large common offset (squared errors, timestamps) lose no precision.
inline MeanStd ComputeMeanStd(const std::vector<double>& values) {
  MeanStd result;
  if (values.empty()) return result;
  for (const double v : values) result.mean += v;
  result.mean /= static_cast<double>(values.size());
  double sum_sq = 0.0;
  for (const double v : values) sum_sq += (v - result.mean) * (v - result.mean);
  result.std = std::sqrt(sum_sq / static_cast<double>(values.size()));
  return result;
}

}  // namespace semchain::eval
