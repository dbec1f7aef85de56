#include "bow/bow_vector.h"

#include <gtest/gtest.h>

namespace semchain::bow {
namespace {

TEST(BowVectorTest, L1ScoreOfIdenticalVectorsIsOne) {
  const BowVector v = {{1, 0.2}, {4, 0.5}, {9, 0.3}};
  EXPECT_DOUBLE_EQ(L1Score(v, v), 1.0);
  // Scale does not matter: the score normalises.
  const BowVector scaled = {{1, 2.0}, {4, 5.0}, {9, 3.0}};
  EXPECT_NEAR(L1Score(v, scaled), 1.0, 1e-12);
}

TEST(BowVectorTest, L1ScoreOfDisjointVectorsIsZero) {
  EXPECT_DOUBLE_EQ(L1Score({{1, 0.5}, {2, 0.5}}, {{3, 0.5}, {4, 0.5}}), 0.0);
  EXPECT_DOUBLE_EQ(L1Score({}, {{3, 1.0}}), 0.0);
}

TEST(BowVectorTest, L1ScoreKnownValue) {
  // |a − b|₁ = 0.5 + 0 + 0.5 = 1, so s = 1 − ½ = 0.5.
  EXPECT_DOUBLE_EQ(L1Score({{0, 0.5}, {1, 0.5}}, {{1, 0.5}, {2, 0.5}}), 0.5);
  // |a − b|₁ = |0.75 − 0.25| + |0.25 − 0.75| = 1: s = 0.5.
  EXPECT_DOUBLE_EQ(L1Score({{0, 0.75}, {1, 0.25}}, {{0, 0.25}, {1, 0.75}}), 0.5);
}

TEST(BowVectorTest, AccumulatorSortsMergesAndNormalises) {
  BowAccumulator accumulator;
  accumulator.Add(5, 1.0);
  accumulator.Add(2, 2.0);
  accumulator.Add(5, 1.0);
  accumulator.Add(7, 0.0);  // a zero weight is dropped
  const BowVector v = accumulator.Finalize();
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[0].first, 2);
  EXPECT_DOUBLE_EQ(v[0].second, 0.5);
  EXPECT_EQ(v[1].first, 5);
  EXPECT_DOUBLE_EQ(v[1].second, 0.5);
}

}  // namespace
}  // namespace semchain::bow
