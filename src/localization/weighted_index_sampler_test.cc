#include "localization/weighted_index_sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "core/rng.h"

namespace semchain::localization {
namespace {

std::vector<double> RandomWeights(std::size_t n, std::uint64_t seed) {
  Rng rng = MakeRng(seed);
  std::exponential_distribution<double> draw(1.0);
  std::vector<double> weights(n);
  for (double& w : weights) w = draw(rng);
  weights[n / 3] = 0.0;  // a particle that must never be drawn
  return weights;
}

// The guide table must answer exactly as std::upper_bound on the partial sums does.
TEST(WeightedIndexSamplerTest, AnswersAsTheBinarySearchOnThePartialSums) {
  const std::vector<double> weights = RandomWeights(1000, 3);
  std::vector<double> sums(weights.size());
  std::partial_sum(weights.begin(), weights.end(), sums.begin());
  const WeightedIndexSampler sampler(weights);
  Rng rng = MakeRng(4);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 20000; ++k) {
    const double r = unit(rng) * sampler.total();
    const auto expected = static_cast<std::size_t>(
        std::min<std::ptrdiff_t>(std::upper_bound(sums.begin(), sums.end(), r) - sums.begin(),
                                 static_cast<std::ptrdiff_t>(sums.size()) - 1));
    ASSERT_EQ(sampler.IndexOf(r), expected) << "r = " << r;
  }
}

// A comb of c teeth draws index i ⌊c·wᵢ/W⌋ or ⌈c·wᵢ/W⌉ times, whatever the offset.
TEST(WeightedIndexSamplerTest, SystematicDrawsGiveEachIndexItsShareWithinOne) {
  const std::vector<double> weights = RandomWeights(500, 7);
  const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
  const WeightedIndexSampler sampler(weights);
  const std::size_t count = 1700;
  for (const double offset : {0.0, 0.25, 0.999}) {
    const std::vector<std::size_t> draws = SystematicDraws(sampler, count, offset);
    ASSERT_EQ(draws.size(), count);
    EXPECT_TRUE(std::is_sorted(draws.begin(), draws.end()));
    std::vector<int> times(weights.size(), 0);
    for (const std::size_t i : draws) ++times[i];
    for (std::size_t i = 0; i < weights.size(); ++i) {
      const double share = static_cast<double>(count) * weights[i] / total;
      EXPECT_GE(times[i], static_cast<int>(std::floor(share))) << "index " << i;
      EXPECT_LE(times[i], static_cast<int>(std::ceil(share))) << "index " << i;
    }
    EXPECT_EQ(times[weights.size() / 3], 0);
  }
}

// Independent draws spread the counts binomially: with the same weights some index is drawn
// two or more times off its share, which the comb never does (the property that makes it the
// low-variance choice).
TEST(WeightedIndexSamplerTest, IndependentDrawsStrayFurtherFromTheShareThanTheComb) {
  const std::vector<double> weights = RandomWeights(500, 7);
  const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
  const WeightedIndexSampler sampler(weights);
  Rng rng = MakeRng(9);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::size_t count = 1700;
  std::vector<int> times(weights.size(), 0);
  for (std::size_t k = 0; k < count; ++k) ++times[sampler.IndexOf(unit(rng) * total)];
  double worst = 0.0;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    worst = std::max(worst, std::abs(times[i] - static_cast<double>(count) * weights[i] / total));
  }
  EXPECT_GT(worst, 2.0);
}

}  // namespace
}  // namespace semchain::localization
