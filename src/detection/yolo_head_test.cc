#include "detection/yolo_head.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace semchain::detection {
namespace {

constexpr float kNever = -100.0f;  // a logit whose softmax weight is negligible (e^-100)

// A 1 x rows x anchors output filled with 'fill'.
cv::Mat Output(int rows, int anchors, float fill) {
  const int sizes[3] = {1, rows, anchors};
  return cv::Mat(3, sizes, CV_32F, cv::Scalar(fill));
}

float& At(cv::Mat& output, int row, int anchor) {
  return output.ptr<float>()[row * output.size[2] + anchor];
}

TEST(DflDistanceTest, EqualLogitsGiveTheMeanBin) {
  const std::vector<float> logits(kRegMax, 0.3f);
  EXPECT_DOUBLE_EQ(DflDistance(logits.data(), 1), 7.5);
}

TEST(DflDistanceTest, MatchesHandComputedExpectations) {
  // Bins 0 and 1 with weights 1 : 3 -> 0.75.
  std::vector<float> logits(kRegMax, kNever);
  logits[0] = 0.0f;
  logits[1] = std::log(3.0f);
  EXPECT_NEAR(DflDistance(logits.data(), 1), 0.75, 1e-6);
  // Bins 4, 5, 6 with weights 1 : 2 : 1 -> 5; one bin alone -> that bin.
  std::fill(logits.begin(), logits.end(), kNever);
  logits[4] = 1.0f;
  logits[5] = 1.0f + std::log(2.0f);
  logits[6] = 1.0f;
  EXPECT_NEAR(DflDistance(logits.data(), 1), 5.0, 1e-6);
  std::fill(logits.begin(), logits.end(), kNever);
  logits[15] = 20.0f;
  EXPECT_NEAR(DflDistance(logits.data(), 1), 15.0, 1e-6);
}

TEST(DflDistanceTest, ReadsStridedLogits) {
  // Every third value is a bin, as in a 1 x 64 x 3 output read for one anchor.
  std::vector<float> data(3 * kRegMax, 50.0f);
  for (int k = 0; k < kRegMax; ++k) data[3 * k] = kNever;
  data[3 * 2] = 0.0f;
  data[3 * 3] = 0.0f;
  EXPECT_NEAR(DflDistance(data.data(), 3), 2.5, 1e-6);
}

TEST(MakeAnchorsTest, OrdersStridesThenRowsThenColumns) {
  const std::vector<Anchor> anchors = MakeAnchors(cv::Size(96, 64));
  ASSERT_EQ(anchors.size(), 12u * 8 + 6 * 4 + 3 * 2);
  EXPECT_FLOAT_EQ(anchors[0].x, 4.0f);
  EXPECT_FLOAT_EQ(anchors[0].y, 4.0f);
  EXPECT_FLOAT_EQ(anchors[0].stride, 8.0f);
  EXPECT_FLOAT_EQ(anchors[13].x, 12.0f);  // row 1, column 1 of stride 8
  EXPECT_FLOAT_EQ(anchors[13].y, 12.0f);
  EXPECT_FLOAT_EQ(anchors[96].x, 8.0f);  // first of stride 16
  EXPECT_FLOAT_EQ(anchors[96].stride, 16.0f);
  EXPECT_FLOAT_EQ(anchors.back().x, 80.0f);  // (2 + 0.5) * 32
  EXPECT_FLOAT_EQ(anchors.back().y, 48.0f);
  EXPECT_FLOAT_EQ(anchors.back().stride, 32.0f);
}

TEST(DecodeHeadTest, DecodesARawHeadAroundItsAnchor) {
  const cv::Size input(64, 64);  // 64 + 16 + 4 anchors
  const std::vector<Anchor> anchors = MakeAnchors(input);
  cv::Mat output = Output(4 * kRegMax + 2, 84, kNever);
  const int a = 64 + 2 * 4 + 1;  // stride 16, row 2, column 1: centre (24, 40)
  // left 1.5 strides (bins 1 and 2 equally), top 1, right 0.25 (bins 0 and 1 as 3 : 1), bottom 0.
  At(output, 0 * kRegMax + 1, a) = 0.0f;
  At(output, 0 * kRegMax + 2, a) = 0.0f;
  At(output, 1 * kRegMax + 1, a) = 5.0f;
  At(output, 2 * kRegMax + 0, a) = std::log(3.0f);
  At(output, 2 * kRegMax + 1, a) = 0.0f;
  At(output, 3 * kRegMax + 0, a) = 0.0f;
  At(output, 4 * kRegMax + 1, a) = 2.0f;  // class 1: sigmoid(2) = 0.8808
  const HeadLayout layout{HeadKind::kRaw, 2, 84};
  const std::vector<Candidate> found = DecodeHead(output, layout, anchors, 0.5);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].class_id, 1);
  EXPECT_NEAR(found[0].score, 1.0 / (1.0 + std::exp(-2.0)), 1e-6);
  EXPECT_NEAR(found[0].box.x, 24.0 - 1.5 * 16, 1e-4);
  EXPECT_NEAR(found[0].box.y, 40.0 - 1.0 * 16, 1e-4);
  EXPECT_NEAR(found[0].box.br().x, 24.0 + 0.25 * 16, 1e-4);
  EXPECT_NEAR(found[0].box.br().y, 40.0, 1e-4);
}

TEST(DecodeHeadTest, DecodesADecodedHeadAndAppliesTheThreshold) {
  const std::vector<Anchor> anchors = MakeAnchors(cv::Size(64, 64));
  cv::Mat output = Output(4 + 3, 84, 0.0f);
  for (int a : {5, 70}) {
    At(output, 0, a) = 30.0f;  // cx, cy, w, h
    At(output, 1, a) = 20.0f;
    At(output, 2, a) = 10.0f;
    At(output, 3, a) = 8.0f;
  }
  At(output, 4 + 2, 5) = 0.9f;
  At(output, 4 + 0, 70) = 0.2f;  // below the threshold
  const std::vector<Candidate> found =
      DecodeHead(output, HeadLayout{HeadKind::kDecoded, 3, 84}, anchors, 0.25);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].class_id, 2);
  EXPECT_FLOAT_EQ(found[0].score, 0.9f);
  EXPECT_DOUBLE_EQ(found[0].box.x, 25.0);
  EXPECT_DOUBLE_EQ(found[0].box.y, 16.0);
  EXPECT_DOUBLE_EQ(found[0].box.width, 10.0);
  EXPECT_DOUBLE_EQ(found[0].box.height, 8.0);
}

TEST(IdentifyHeadTest, RecognisesBothHeads) {
  const cv::Size input(64, 64);
  Result<HeadLayout> raw = IdentifyHead(Output(64 + 5, 84, 0.0f), 5, input);
  ASSERT_TRUE(raw.ok()) << raw.status().message();
  EXPECT_EQ(raw->kind, HeadKind::kRaw);
  EXPECT_EQ(raw->anchors, 84);
  Result<HeadLayout> decoded = IdentifyHead(Output(4 + 5, 84, 0.0f), 5, input);
  ASSERT_TRUE(decoded.ok()) << decoded.status().message();
  EXPECT_EQ(decoded->kind, HeadKind::kDecoded);
}

TEST(IdentifyHeadTest, NamesWhatIsWrong) {
  const cv::Size input(64, 64);
  const int sizes[4] = {1, 67, 8, 8};
  Result<HeadLayout> four_d = IdentifyHead(cv::Mat(4, sizes, CV_32F), 3, input);
  ASSERT_FALSE(four_d.ok());
  EXPECT_EQ(four_d.status().message(),
            "the model's output is 1x67x8x8, expected 1 x (64 + classes) x anchors (raw head) "
            "or 1 x (4 + classes) x anchors (decoded head)");
  Result<HeadLayout> mismatch = IdentifyHead(Output(64 + 80, 84, 0.0f), 3, input);
  ASSERT_FALSE(mismatch.ok());
  EXPECT_EQ(mismatch.status().message(),
            "class-count mismatch: the model's output has 144 rows per anchor, which fits 80 "
            "classes (raw head) or 140 classes (decoded head), but there are 3 class names");
  Result<HeadLayout> transposed = IdentifyHead(Output(84, 67, 0.0f), 3, input);
  ASSERT_FALSE(transposed.ok());
  EXPECT_NE(transposed.status().message().find("transposed"), std::string::npos);
  Result<HeadLayout> anchors = IdentifyHead(Output(67, 8400, 0.0f), 3, input);
  ASSERT_FALSE(anchors.ok());
  EXPECT_EQ(anchors.status().message(),
            "the model's output is 1x67x8400: 8400 anchors, but strides 8, 16, 32 at 64x64 "
            "give 84");
}

}  // namespace
}  // namespace semchain::detection
