#include "detection/letterbox.h"

#include <gtest/gtest.h>

namespace semchain::detection {
namespace {

void ExpectRoundTrip(const Letterbox& box) {
  for (const cv::Point2d p : {cv::Point2d(0, 0), cv::Point2d(box.image.width, box.image.height),
                              cv::Point2d(17.25, 3.5), cv::Point2d(box.image.width / 3.0, 1.0)}) {
    const cv::Point2d back = box.ToImage(box.ToInput(p));
    EXPECT_NEAR(back.x, p.x, 1e-9);
    EXPECT_NEAR(back.y, p.y, 1e-9);
  }
  // The image's corners land on the scaled area's corners.
  const cv::Point2d far = box.ToInput(cv::Point2d(box.image.width, box.image.height));
  EXPECT_DOUBLE_EQ(far.x, box.pad_left + box.scaled.width);
  EXPECT_DOUBLE_EQ(far.y, box.pad_top + box.scaled.height);
}

TEST(LetterboxTest, FitsALandscapeImageIntoANonSquareInput) {
  const Letterbox box = FitLetterbox(cv::Size(640, 480), cv::Size(320, 256));
  EXPECT_EQ(box.scaled, cv::Size(320, 240));
  EXPECT_EQ(box.pad_left, 0);
  EXPECT_EQ(box.pad_top, 8);
  EXPECT_DOUBLE_EQ(box.scale_x(), 0.5);
  EXPECT_EQ(box.ToInput(cv::Point2d(100, 50)), cv::Point2d(50, 33));
  ExpectRoundTrip(box);
}

TEST(LetterboxTest, FitsAPortraitImageIntoAWideInput) {
  const Letterbox box = FitLetterbox(cv::Size(480, 640), cv::Size(640, 320));
  EXPECT_EQ(box.scaled, cv::Size(240, 320));
  EXPECT_EQ(box.pad_left, 200);
  EXPECT_EQ(box.pad_top, 0);
  EXPECT_EQ(box.ToImage(cv::Point2d(200, 0)), cv::Point2d(0, 0));
  EXPECT_EQ(box.ToImage(cv::Point2d(440, 320)), cv::Point2d(480, 640));
  ExpectRoundTrip(box);
}

TEST(LetterboxTest, RoundsOddSizesAndPutsTheOddPadPixelLast) {
  const Letterbox box = FitLetterbox(cv::Size(333, 111), cv::Size(96, 65));
  EXPECT_EQ(box.scaled, cv::Size(96, 32));  // 111 * 96 / 333 = 32
  EXPECT_EQ(box.pad_left, 0);
  EXPECT_EQ(box.pad_top, 16);  // 33 rows of padding: 16 above, 17 below
  ExpectRoundTrip(box);
  const Letterbox up = FitLetterbox(cv::Size(50, 30), cv::Size(128, 128));
  EXPECT_EQ(up.scaled, cv::Size(128, 77));  // 30 * 2.56 = 76.8
  EXPECT_EQ(up.pad_top, 25);
  ExpectRoundTrip(up);
}

TEST(LetterboxTest, PadsWithGreyAndKeepsTheImage) {
  cv::Mat image(480, 640, CV_8UC3, cv::Scalar(10, 200, 30));
  const Letterbox box = FitLetterbox(image.size(), cv::Size(320, 256));
  const cv::Mat input = ApplyLetterbox(image, box);
  ASSERT_EQ(input.size(), cv::Size(320, 256));
  EXPECT_EQ(input.at<cv::Vec3b>(0, 0), cv::Vec3b(114, 114, 114));
  EXPECT_EQ(input.at<cv::Vec3b>(7, 319), cv::Vec3b(114, 114, 114));
  EXPECT_EQ(input.at<cv::Vec3b>(8, 0), cv::Vec3b(10, 200, 30));
  EXPECT_EQ(input.at<cv::Vec3b>(247, 319), cv::Vec3b(10, 200, 30));
  EXPECT_EQ(input.at<cv::Vec3b>(248, 100), cv::Vec3b(114, 114, 114));
}

}  // namespace
}  // namespace semchain::detection
