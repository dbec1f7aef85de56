#include "eval/statistics.h"

#include <gtest/gtest.h>

namespace semchain::eval {
namespace {

TEST(StatisticsTest, PopulationAndSampleDeviationsOfKnownValues) {
  const std::vector<double> values = {2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0};
  const MeanStd population = ComputeMeanStd(values);
  EXPECT_DOUBLE_EQ(population.mean, 5.0);
  EXPECT_DOUBLE_EQ(population.std, 2.0);  // Σ (v − 5)² = 32, / 8
  const MeanStd sample = ComputeSampleMeanStd(values);
  EXPECT_DOUBLE_EQ(sample.mean, 5.0);
  EXPECT_DOUBLE_EQ(sample.std, std::sqrt(32.0 / 7.0));
}

TEST(StatisticsTest, FewValues) {
  EXPECT_DOUBLE_EQ(ComputeMeanStd({}).mean, 0.0);
  EXPECT_DOUBLE_EQ(ComputeSampleMeanStd({}).std, 0.0);
  const MeanStd one = ComputeSampleMeanStd({3.5});
  EXPECT_DOUBLE_EQ(one.mean, 3.5);
  EXPECT_DOUBLE_EQ(one.std, 0.0);
  // A large common offset loses nothing (two passes).
  EXPECT_NEAR(ComputeMeanStd({1e9 + 1.0, 1e9 + 3.0}).std, 1.0, 1e-9);
}

TEST(StatisticsTest, MedianOfOddAndEvenCounts) {
  EXPECT_FALSE(Median({}).has_value());
  EXPECT_DOUBLE_EQ(*Median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_DOUBLE_EQ(*Median({4.0, 1.0, 3.0, 2.0}), 2.5);
}

TEST(PercentileTest, NearestRank) {
  const std::vector<double> values = {7, 1, 9, 3, 5, 2, 8, 4, 10, 6};
  EXPECT_DOUBLE_EQ(Percentile(values, 50.0), 5.0);
  EXPECT_DOUBLE_EQ(Percentile(values, 95.0), 10.0);
  EXPECT_DOUBLE_EQ(Percentile(values, 90.0), 9.0);
  EXPECT_DOUBLE_EQ(Percentile(values, 100.0), 10.0);
  EXPECT_DOUBLE_EQ(Percentile(values, 1.0), 1.0);
  EXPECT_DOUBLE_EQ(Percentile({}, 50.0), 0.0);
}

}  // namespace
}  // namespace semchain::eval
