#include "localization/kld_sampling.h"

#include <gtest/gtest.h>

namespace semchain::localization {
namespace {

// n = χ²_{k−1, 1−δ} / (2ε): with the 99 % quantile (z = 2.3263) the Wilson-Hilferty form is
// within 0.2 % of the tabulated χ² quantiles 23.209 (10 dof) and 135.807 (100 dof).
TEST(KldSamplingTest, BoundMatchesTheChiSquareQuantile) {
  EXPECT_NEAR(KldSampleBound(11, 0.05, 2.3263), 23.209 / 0.1, 0.002 * 232.09);
  EXPECT_NEAR(KldSampleBound(101, 0.05, 2.3263), 135.807 / 0.1, 0.002 * 1358.07);
  // nav2's defaults (pf_err 0.05, pf_z 0.99) for k = 2: 10 (1 − 2/9 + 0.99 √(2/9))³ = 19.273.
  EXPECT_NEAR(KldSampleBound(2, 0.05, 0.99), 19.2731, 1e-3);
  EXPECT_EQ(KldSampleBound(1, 0.05, 0.99), 0.0);
}

TEST(KldSamplingTest, BoundGrowsWithBinsAndShrinksWithError) {
  EXPECT_LT(KldSampleBound(10, 0.05, 0.99), KldSampleBound(20, 0.05, 0.99));
  EXPECT_GT(KldSampleBound(10, 0.01, 0.99), KldSampleBound(10, 0.05, 0.99));
}

TEST(KldSamplingTest, PoseBinsCountOccupiedBins) {
  PoseBins bins(0.5, 0.5, 0.2);
  EXPECT_TRUE(bins.Insert(Pose2(0.1, 0.1, 0.05)));
  EXPECT_FALSE(bins.Insert(Pose2(0.4, 0.2, 0.15)));
  EXPECT_TRUE(bins.Insert(Pose2(-0.1, 0.1, 0.05)));  // negative x: its own bin
  EXPECT_TRUE(bins.Insert(Pose2(0.1, 0.1, -0.05)));
  EXPECT_EQ(bins.count(), 3);
}

}  // namespace
}  // namespace semchain::localization
