#include "mapping/resampling.h"

#include <gtest/gtest.h>

#include <numeric>

#include "mapping/genetic_resampling.h"

namespace semchain::mapping {
namespace {

TEST(ResamplingTest, NormalizeLogWeightsSumsToOneAndSurvivesHugeLogs) {
  const std::vector<double> weights = NormalizeLogWeights({-1000.0, -1000.0 + std::log(3.0)});
  EXPECT_NEAR(weights[0], 0.25, 1e-12);
  EXPECT_NEAR(weights[1], 0.75, 1e-12);
  const std::vector<double> tempered = NormalizeLogWeights({0.0, 2.0 * std::log(3.0)}, 0.5);
  EXPECT_NEAR(tempered[1], 0.75, 1e-12);
}

TEST(ResamplingTest, EffectiveSampleSizeEquation3) {
  EXPECT_NEAR(EffectiveSampleSize({0.25, 0.25, 0.25, 0.25}), 4.0, 1e-12);
  EXPECT_NEAR(EffectiveSampleSize({1.0, 0.0, 0.0, 0.0}), 1.0, 1e-12);
  EXPECT_NEAR(EffectiveSampleSize({0.5, 0.5, 0.0}), 2.0, 1e-12);
}

TEST(ResamplingTest, LowVarianceResampleIsProportionalAndOrdered) {
  Rng rng = MakeRng(7);
  const std::vector<int> indices = LowVarianceResample({0.5, 0.25, 0.0, 0.25}, 8, rng);
  ASSERT_EQ(indices.size(), 8u);
  EXPECT_TRUE(std::is_sorted(indices.begin(), indices.end()));
  EXPECT_EQ(std::count(indices.begin(), indices.end(), 0), 4);
  EXPECT_EQ(std::count(indices.begin(), indices.end(), 1), 2);
  EXPECT_EQ(std::count(indices.begin(), indices.end(), 2), 0);
  EXPECT_EQ(std::count(indices.begin(), indices.end(), 3), 2);
}

TEST(AdaptiveRateTest, Equations9And10) {
  // Below the mean fitness: the first rate; at the mean: half way; at the max: near rate 2.
  EXPECT_DOUBLE_EQ(AdaptiveRate(0.05, 0.1, 0.5, 0.7, 0.5, 9.903438), 0.7);
  EXPECT_NEAR(AdaptiveRate(0.1, 0.1, 0.5, 0.7, 0.5, 9.903438), 0.6, 1e-12);
  EXPECT_NEAR(AdaptiveRate(0.5, 0.1, 0.5, 0.7, 0.5, 9.903438), 0.5, 1e-8);
  const double middle = AdaptiveRate(0.3, 0.1, 0.5, 0.1, 0.01, 9.903438);
  EXPECT_GT(middle, 0.01);
  EXPECT_LT(middle, 0.055);
}

class GeneticResamplingTest : public ::testing::Test {
 protected:
  // Ten particles: 0 and 1 are high (> 2/N = 0.2), 2–4 medium, 5–9 low (< 1/(2N) = 0.05).
  void SetUp() override {
    weights_ = {0.40, 0.30, 0.10, 0.10, 0.06, 0.02, 0.01, 0.005, 0.003, 0.002};
    const double sum = std::accumulate(weights_.begin(), weights_.end(), 0.0);
    for (double& w : weights_) w /= sum;
    for (int i = 0; i < 10; ++i) {
      Particle p;
      p.pose = Pose2(i * 0.01, 0.0, 0.0);  // all within the crossover distance
      p.map = std::make_shared<OccupancyGrid>();
      particles_.push_back(p);
    }
    original_ = particles_;
  }
  std::vector<double> weights_;
  std::vector<Particle> particles_;
  std::vector<Particle> original_;
};

TEST_F(GeneticResamplingTest, ClassifiesByEquation8AndReplacesOnlyLowParticles) {
  GeneticResamplingOptions options;
  options.enabled = true;
  options.crossover_rate_1 = options.crossover_rate_2 = 1.0;  // every low particle is crossed
  options.mutation_rate_1 = options.mutation_rate_2 = 0.0;
  Rng rng = MakeRng(3);
  std::vector<double> weights = weights_;
  const GeneticStatistics stats = GeneticResample(options, &weights, &particles_, rng);
  EXPECT_EQ(stats.high, 2);
  EXPECT_EQ(stats.medium, 3);
  EXPECT_EQ(stats.low, 5);
  EXPECT_EQ(stats.crossovers, 5);
  for (int i = 0; i < 5; ++i) {  // high and medium particles keep pose and map
    EXPECT_EQ(particles_[i].map, original_[i].map) << i;
    EXPECT_DOUBLE_EQ(particles_[i].pose.x, original_[i].pose.x) << i;
  }
  for (int i = 5; i < 10; ++i) {  // children: a high parent's map, a pose between the parents
    const bool from_0 = particles_[i].map == original_[0].map;
    const bool from_1 = particles_[i].map == original_[1].map;
    EXPECT_TRUE(from_0 || from_1) << i;
    const double high_x = from_0 ? 0.0 : 0.01;
    EXPECT_GE(particles_[i].pose.x, std::min(high_x, original_[i].pose.x) - 1e-12);
    EXPECT_LE(particles_[i].pose.x, std::max(high_x, original_[i].pose.x) + 1e-12);
  }
  EXPECT_NEAR(std::accumulate(weights.begin(), weights.end(), 0.0), 1.0, 1e-12);
  // Medium particles keep their share (up to the renormalisation of the dropped low mass).
  EXPECT_NEAR(weights[2] / weights[3], 1.0, 1e-12);
  EXPECT_GT(EffectiveSampleSize(weights), EffectiveSampleSize(weights_));
}

TEST_F(GeneticResamplingTest, ZeroRatesChangeNothing) {
  GeneticResamplingOptions options;
  options.crossover_rate_1 = options.crossover_rate_2 = 0.0;
  Rng rng = MakeRng(3);
  std::vector<double> weights = weights_;
  const GeneticStatistics stats = GeneticResample(options, &weights, &particles_, rng);
  EXPECT_EQ(stats.crossovers, 0);
  EXPECT_EQ(stats.mutations, 0);
  for (int i = 0; i < 10; ++i) {
    EXPECT_EQ(particles_[i].map, original_[i].map);
    EXPECT_NEAR(weights[i], weights_[i], 1e-12);
  }
}

TEST_F(GeneticResamplingTest, MutationOnlyTouchesChildren) {
  GeneticResamplingOptions options;
  options.crossover_rate_1 = options.crossover_rate_2 = 1.0;
  options.crossover_max_blend = 0.0;  // children start exactly at their high parent
  options.mutation_rate_1 = options.mutation_rate_2 = 1.0;
  Rng rng = MakeRng(5);
  std::vector<double> weights = weights_;
  const GeneticStatistics stats = GeneticResample(options, &weights, &particles_, rng);
  EXPECT_EQ(stats.mutations, 5);
  for (int i = 0; i < 5; ++i) EXPECT_DOUBLE_EQ(particles_[i].pose.x, original_[i].pose.x);
  for (int i = 5; i < 10; ++i) {
    EXPECT_NE(particles_[i].pose.x, 0.0);
    EXPECT_NE(particles_[i].pose.x, 0.01);
  }
}

}  // namespace
}  // namespace semchain::mapping
