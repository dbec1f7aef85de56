#include "detection/class_nms.h"

#include <gtest/gtest.h>

namespace semchain::detection {
namespace {

Candidate Make(double x, double y, double w, double h, int class_id, float score) {
  return {cv::Rect2d(x, y, w, h), class_id, score};
}

TEST(ClassWiseNmsTest, KeepsTheBestOfOverlappingSameClassBoxes) {
  // IoU of the first two: 90 / 110 = 0.82.
  const std::vector<Candidate> candidates = {Make(0, 0, 10, 10, 0, 0.6f),
                                             Make(1, 0, 10, 10, 0, 0.9f)};
  EXPECT_EQ(ClassWiseNms(candidates, 0.45, 100), (std::vector<int>{1}));
}

TEST(ClassWiseNmsTest, KeepsOverlappingBoxesOfDifferentClasses) {
  const std::vector<Candidate> candidates = {
      Make(0, 0, 10, 10, 0, 0.6f), Make(1, 0, 10, 10, 1, 0.9f), Make(0, 1, 10, 10, 1, 0.5f)};
  // Class 1's two boxes overlap (IoU 81 / 119 = 0.68): the weaker goes; class 0's box stays.
  EXPECT_EQ(ClassWiseNms(candidates, 0.45, 100), (std::vector<int>{1, 0}));
}

TEST(ClassWiseNmsTest, KeepsSameClassBoxesBelowTheThresholdBestFirst) {
  // IoU 50 / 150 = 0.33, below 0.45; above 0.3.
  const std::vector<Candidate> candidates = {
      Make(0, 0, 10, 10, 2, 0.3f), Make(5, 0, 10, 10, 2, 0.8f), Make(40, 40, 5, 5, 2, 0.5f)};
  EXPECT_EQ(ClassWiseNms(candidates, 0.45, 100), (std::vector<int>{1, 2, 0}));
  EXPECT_EQ(ClassWiseNms(candidates, 0.3, 100), (std::vector<int>{1, 2}));
  EXPECT_EQ(ClassWiseNms(candidates, 0.45, 2), (std::vector<int>{1, 2}));
}

TEST(ClassWiseNmsTest, MergesIdenticalBoxes) {
  const std::vector<Candidate> candidates = {Make(3, 4, 20, 30, 1, 0.7f),
                                             Make(3, 4, 20, 30, 1, 0.7f)};
  EXPECT_EQ(ClassWiseNms(candidates, 0.45, 100).size(), 1u);
  EXPECT_TRUE(ClassWiseNms({}, 0.45, 100).empty());
}

}  // namespace
}  // namespace semchain::detection
