#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

namespace semchain::eval {

struct MeanStd {
  double mean = 0.0;
  double std = 0.0;  // 0 for n <= 1
};

namespace internal {

// The mean and the sum of squared deviations from it. Two passes, so that values with a large
// common offset (squared errors, timestamps) lose no precision.
inline std::pair<double, double> MeanAndSquaredDeviations(const std::vector<double>& values) {
  double mean = 0.0;
  for (const double v : values) mean += v;
  mean /= static_cast<double>(values.size());
  double sum_sq = 0.0;
  for (const double v : values) sum_sq += (v - mean) * (v - mean);
  return {mean, sum_sq};
}

}  // namespace internal

// Mean and population standard deviation (divides by n) of 'values'; both 0 when empty.
inline MeanStd ComputeMeanStd(const std::vector<double>& values) {
  if (values.empty()) return {};
  const auto [mean, sum_sq] = internal::MeanAndSquaredDeviations(values);
  return {mean, std::sqrt(sum_sq / static_cast<double>(values.size()))};
}

// Mean and sample standard deviation (divides by n − 1): the spread of a few runs (seeds), whose
// mean is itself estimated from them. Both 0 when empty, the deviation 0 for one value.
inline MeanStd ComputeSampleMeanStd(const std::vector<double>& values) {
  if (values.empty()) return {};
  const auto [mean, sum_sq] = internal::MeanAndSquaredDeviations(values);
  const double n = static_cast<double>(values.size());
  return {mean, values.size() > 1 ? std::sqrt(sum_sq / (n - 1.0)) : 0.0};
}

// The median (the mean of the two middle values for an even count); none for no values.
inline std::optional<double> Median(std::vector<double> values) {
  if (values.empty()) return std::nullopt;
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

// The nearest-rank p-th percentile (0 < p <= 100) of 'values' (p = 100: the largest); 0 for none.
inline double Percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double n = static_cast<double>(values.size());
  const std::size_t index = static_cast<std::size_t>(std::clamp(std::ceil(p / 100.0 * n), 1.0, n));
  return values[index - 1];
}

}  // namespace semchain::eval
