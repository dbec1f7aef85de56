#include "io/yolo_labels.h"

#include <gtest/gtest.h>

namespace semchain {
namespace {

std::string ErrorOf(const Result<std::vector<YoloLabel>>& result) {
  return result.ok() ? "" : result.status().message();
}

TEST(YoloLabelsTest, ParsesLinesIntoPixelBoxes) {
  const Result<std::vector<YoloLabel>> labels =
      ParseYoloLabels("3 0.5 0.25 0.2 0.1\r\n\n9 0.05 0.95 0.1 0.1\n", "a.txt", 10);
  ASSERT_TRUE(labels.ok()) << labels.status().message();
  ASSERT_EQ(labels->size(), 2u);
  EXPECT_EQ((*labels)[0].class_id, 3);
  const std::array<double, 4> box = (*labels)[0].PixelBox(320, 256);
  EXPECT_DOUBLE_EQ(box[0], 128.0);
  EXPECT_DOUBLE_EQ(box[1], 51.2);
  EXPECT_DOUBLE_EQ(box[2], 192.0);
  EXPECT_DOUBLE_EQ(box[3], 76.8);
  EXPECT_EQ((*labels)[1].class_id, 9);
}

TEST(YoloLabelsTest, RejectsBadLinesNamingThem) {
  EXPECT_EQ(ErrorOf(ParseYoloLabels("0 0.5 0.5 0.1 0.1\n10 0.5 0.5 0.1 0.1\n", "l.txt", 10)),
            "l.txt:2: class 10 out of range (nc 10)");
  EXPECT_EQ(ErrorOf(ParseYoloLabels("-1 0.5 0.5 0.1 0.1\n", "l.txt", 10)),
            "l.txt:1: class -1 out of range (nc 10)");
  EXPECT_EQ(ErrorOf(ParseYoloLabels("door 0.5 0.5 0.1 0.1\n", "l.txt", 10)),
            "l.txt:1: class 'door' is not an integer");
  EXPECT_EQ(ErrorOf(ParseYoloLabels("1 0.5 0.5 0.1\n", "l.txt", 10)),
            "l.txt:1: expected 'class cx cy w h'");
  EXPECT_EQ(ErrorOf(ParseYoloLabels("1 0.5 0.5 0.1 0.1 7\n", "l.txt", 10)),
            "l.txt:1: expected 'class cx cy w h', got more fields");
  EXPECT_EQ(ErrorOf(ParseYoloLabels("1 0.5 nan 0.1 0.1\n", "l.txt", 10)),
            "l.txt:1: 'nan' is not a finite number");
  EXPECT_EQ(ErrorOf(ParseYoloLabels("1 1.5 0.5 0.1 0.1\n", "l.txt", 10)),
            "l.txt:1: '1.5' lies outside [0, 1]");
  EXPECT_EQ(ErrorOf(ParseYoloLabels("1 0.98 0.5 0.1 0.1\n", "l.txt", 10)),
            "l.txt:1: the box is empty or reaches outside the image");
  EXPECT_EQ(ErrorOf(ParseYoloLabels("1 0.5 0.5 0 0.1\n", "l.txt", 10)),
            "l.txt:1: the box is empty or reaches outside the image");
}

}  // namespace
}  // namespace semchain
