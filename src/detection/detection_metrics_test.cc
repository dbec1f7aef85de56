#include "detection/detection_metrics.h"

#include <gtest/gtest.h>

#include "detection/testing/detections.h"

namespace semchain::detection {
namespace {

using testing::Predicted;

TEST(DetectionMetricsTest, IouOfKnownBoxes) {
  EXPECT_DOUBLE_EQ(BoxIou({0, 0, 10, 10}, {0, 0, 10, 10}), 1.0);
  EXPECT_DOUBLE_EQ(BoxIou({0, 0, 10, 10}, {5, 0, 15, 10}), 50.0 / 150.0);
  EXPECT_DOUBLE_EQ(BoxIou({0, 0, 10, 10}, {10, 0, 20, 10}), 0.0);
}

TEST(DetectionMetricsTest, PerfectDetectionsScoreOne) {
  DetectionEvaluator evaluator(3);
  evaluator.AddImage({Predicted(0, 0.9, 0, 0, 10, 10), Predicted(2, 0.8, 20, 20, 40, 50)},
                     {{0, {0, 0, 10, 10}}, {2, {20, 20, 40, 50}}});
  const DetectionAccuracy accuracy = evaluator.Evaluate();
  EXPECT_DOUBLE_EQ(accuracy.map50, 1.0);
  EXPECT_DOUBLE_EQ(accuracy.map50_95, 1.0);
  EXPECT_DOUBLE_EQ(accuracy.precision, 1.0);
  EXPECT_DOUBLE_EQ(accuracy.recall, 1.0);
  EXPECT_EQ(accuracy.classes[1].truths, 0);  // no truth: not averaged
}

// Two truths; the best-scoring detection is a false positive, then both truths are found:
// precision 0, 1/2, 2/3 at recall 0, 1/2, 1. The envelope is 2/3 at every recall: AP = 2/3.
TEST(DetectionMetricsTest, AveragePrecisionFollowsTheEnvelope) {
  DetectionEvaluator evaluator(1);
  evaluator.AddImage({Predicted(0, 0.9, 100, 100, 110, 110), Predicted(0, 0.8, 0, 0, 10, 10),
                      Predicted(0, 0.7, 20, 0, 30, 10)},
                     {{0, {0, 0, 10, 10}}, {0, {20, 0, 30, 10}}});
  const DetectionAccuracy accuracy = evaluator.Evaluate();
  EXPECT_NEAR(accuracy.map50, 2.0 / 3.0, 1e-12);
  // At the best F1 (confidence above 0.7 … 0.8 keeps all three, or drop the FP: above 0.9 nothing
  // is left) precision 2/3 and recall 1 give F1 0.8.
  EXPECT_NEAR(accuracy.recall, 1.0, 1e-12);
  EXPECT_NEAR(accuracy.precision, 2.0 / 3.0, 1e-12);
}

// A box shifted so that its IoU is 0.6 counts at 0.50, 0.55 and 0.60 only: AP@0.5:0.95 = 3/10.
TEST(DetectionMetricsTest, StricterThresholdsRejectLooseBoxes) {
  DetectionEvaluator evaluator(1);
  // Truth 0..10 × 0..10; prediction 2.5..12.5: IoU = 75 / 125 = 0.6.
  evaluator.AddImage({Predicted(0, 0.9, 2.5, 0, 12.5, 10)}, {{0, {0, 0, 10, 10}}});
  const DetectionAccuracy accuracy = evaluator.Evaluate();
  EXPECT_DOUBLE_EQ(accuracy.map50, 1.0);
  EXPECT_NEAR(accuracy.map50_95, 0.3, 1e-12);
}

// A truth found twice: the second box is a false positive; a missed truth lowers recall.
TEST(DetectionMetricsTest, DuplicatesAndMissesCount) {
  DetectionEvaluator evaluator(1);
  evaluator.AddImage({Predicted(0, 0.9, 0, 0, 10, 10), Predicted(0, 0.8, 0, 0, 10, 10)},
                     {{0, {0, 0, 10, 10}}, {0, {50, 50, 60, 60}}});
  const DetectionAccuracy accuracy = evaluator.Evaluate();
  // Precision 1, 1/2 at recall 1/2: AP = 51 / 101 (recall 0 … 0.5 at precision 1).
  EXPECT_NEAR(accuracy.map50, 51.0 / 101.0, 1e-12);
  EXPECT_NEAR(accuracy.recall, 0.5, 1e-12);
  EXPECT_NEAR(accuracy.precision, 1.0, 1e-12);
}

}  // namespace
}  // namespace semchain::detection
