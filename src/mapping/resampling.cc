#include "mapping/resampling.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "core/check.h"

namespace semchain::mapping {

std::vector<double> NormalizeLogWeights(const std::vector<double>& log_weights, double gain) {
  SEMCHAIN_CHECK(!log_weights.empty());
  const double max = *std::max_element(log_weights.begin(), log_weights.end());
  std::vector<double> weights(log_weights.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < log_weights.size(); ++i) {
    weights[i] = std::exp(gain * (log_weights[i] - max));
    sum += weights[i];
  }
  for (double& w : weights) w /= sum;
  return weights;
}

double EffectiveSampleSize(const std::vector<double>& normalized_weights) {
  double sum_of_squares = 0.0;
  for (const double w : normalized_weights) sum_of_squares += w * w;
  return sum_of_squares > 0.0 ? 1.0 / sum_of_squares : 0.0;
}

std::vector<int> LowVarianceResample(const std::vector<double>& normalized_weights, int count,
                                     Rng& rng) {
  SEMCHAIN_CHECK(!normalized_weights.empty() && count > 0);
  std::vector<int> indices;
  indices.reserve(static_cast<std::size_t>(count));
  const double step = 1.0 / count;
  double target = std::uniform_real_distribution<double>(0.0, step)(rng);
  double cumulative = normalized_weights[0];
  int i = 0;
  const int last = static_cast<int>(normalized_weights.size()) - 1;
  for (int m = 0; m < count; ++m) {
    while (target > cumulative && i < last) cumulative += normalized_weights[++i];
    indices.push_back(i);
    target += step;
  }
  return indices;
}

}  // namespace semchain::mapping
