#include "detection/confusion_matrix.h"

#include <gtest/gtest.h>

#include "detection/testing/detections.h"

namespace semchain::detection {
namespace {

using testing::Predicted;

// A sofa named a bed, a chair found, a stool missed, a bed seen where there is nothing, and a
// detection below the confidence bar that counts for nothing.
TEST(ConfusionMatrixTest, CountsNamesMissesAndUnpairedDetections) {
  constexpr int kChair = 0, kStool = 1, kSofa = 2, kBed = 3, kMissed = 4;
  ConfusionMatrix matrix(4, {.min_score = 0.4, .min_iou = 0.45});
  matrix.AddImage(
      {Predicted(kBed, 0.9, 0, 0, 100, 50), Predicted(kChair, 0.6, 200, 0, 240, 60),
       Predicted(kBed, 0.5, 300, 100, 400, 160), Predicted(kStool, 0.3, 120, 0, 150, 30)},
      {{kSofa, {2, 0, 100, 52}}, {kChair, {200, 2, 240, 60}}, {kStool, {120, 0, 150, 30}}});
  EXPECT_EQ(matrix.Count(kSofa, kBed), 1);
  EXPECT_EQ(matrix.Count(kSofa, kSofa), 0);
  EXPECT_EQ(matrix.Count(kChair, kChair), 1);
  EXPECT_EQ(matrix.Count(kStool, kMissed), 1);  // its only box is below the bar
  EXPECT_EQ(matrix.Unpaired(kBed), 1);
  EXPECT_EQ(matrix.Unpaired(kStool), 0);
  int total = 0;
  for (int t = 0; t <= 4; ++t) {
    for (int d = 0; d <= 4; ++d) total += t < 4 ? matrix.Count(t, d) : matrix.Unpaired(d);
  }
  EXPECT_EQ(total, 4);  // three labelled objects and one unpaired detection
}

// Pairs are one to one, largest overlap first: of two detections on one object the better
// placed is paired with it whatever its score, and the other is unpaired; two objects side by
// side each keep the detection that overlaps them most.
TEST(ConfusionMatrixTest, PairsOneToOneLargestOverlapFirst) {
  ConfusionMatrix matrix(3);
  matrix.AddImage({Predicted(1, 0.9, 0, 0, 14, 10), Predicted(0, 0.5, 0, 0, 10, 10)},
                  {{0, {0, 0, 10, 10}}});
  EXPECT_EQ(matrix.Count(0, 0), 1);
  EXPECT_EQ(matrix.Count(0, 1), 0);
  EXPECT_EQ(matrix.Unpaired(1), 1);
  ConfusionMatrix side_by_side(3);
  side_by_side.AddImage({Predicted(2, 0.9, 8, 0, 20, 10), Predicted(1, 0.8, 0, 0, 11, 10)},
                        {{1, {0, 0, 10, 10}}, {2, {10, 0, 20, 10}}});
  EXPECT_EQ(side_by_side.Count(1, 1), 1);
  EXPECT_EQ(side_by_side.Count(2, 2), 1);
  EXPECT_EQ(side_by_side.Unpaired(1) + side_by_side.Unpaired(2), 0);
}

}  // namespace
}  // namespace semchain::detection
