#include "semantic/keyframe_images.h"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/core.hpp>

#include "io/rgbd_frame_io.h"

namespace semchain::semantic {
namespace {

namespace fs = std::filesystem;

// A distinct RGB image per value (so that a mix-up of frames shows).
cv::Mat Image(int value) {
  cv::Mat rgb(48, 64, CV_8UC3, cv::Scalar(value, 255 - value, value / 2));
  rgb(cv::Rect(value % 40, 8, 16, 16)).setTo(cv::Scalar(0, 0, 255));
  return rgb;
}

Keyframe Named(const std::string& frame) { return Keyframe{frame, 0.0, Pose2(), {}}; }

bool Same(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

TEST(KeyframeImagesTest, PairsImagesAndRecordsByStampInEitherOrder) {
  KeyframeImages images;
  images.AddImage(1.0, Image(10));  // image first
  images.AddFrame("frames/000001", 1.0);
  images.AddFrame("frames/000002", 2.0);  // record first
  images.AddImage(2.0005, Image(20));     // within the 1 ms tolerance
  images.AddFrame("frames/000003", 3.0);
  images.AddImage(3.1, Image(30));  // a different moment: not this record's image
  EXPECT_TRUE(images.Has("frames/000001"));
  EXPECT_TRUE(images.Has("frames/000002"));
  EXPECT_FALSE(images.Has("frames/000003"));

  const fs::path dir = fs::path(testing::TempDir()) / "keyframe_images_pairs";
  fs::remove_all(dir);
  const Result<std::vector<Keyframe>> written =
      images.Write(dir, {Named("frames/000001"), Named("frames/000002"), Named("frames/000003")});
  ASSERT_TRUE(written.ok()) << written.status().message();
  ASSERT_EQ(written->size(), 2u);  // the imageless keyframe is left out
  EXPECT_EQ((*written)[0].frame, "frames/000001");
  const Result<cv::Mat> first = ReadColorImage(ColorImagePath(dir, "frames/000001"));
  const Result<cv::Mat> second = ReadColorImage(ColorImagePath(dir, "frames/000002"));
  ASSERT_TRUE(first.ok() && second.ok());
  EXPECT_TRUE(Same(*first, Image(10)));  // lossless, RGB order kept
  EXPECT_TRUE(Same(*second, Image(20)));
  EXPECT_FALSE(fs::exists(ColorImagePath(dir, "frames/000003")));
}

TEST(KeyframeImagesTest, KeepsOnlyFramesThatAreKeyframesAndBoundsThePending) {
  KeyframeImageOptions options;
  options.pending = 2;
  KeyframeImages images(options);
  for (int i = 0; i < 5; ++i) images.AddImage(i, Image(i));
  // Only the last two images still wait for their records.
  images.AddFrame("old", 0.0);
  images.AddFrame("recent", 4.0);
  EXPECT_FALSE(images.Has("old"));
  EXPECT_TRUE(images.Has("recent"));
  images.AddFrameImage("camera/7", Image(7));
  EXPECT_EQ(images.size(), 2u);
  EXPECT_GT(images.bytes(), 0u);

  const fs::path dir = fs::path(testing::TempDir()) / "keyframe_images_subset";
  fs::remove_all(dir);
  const Result<std::vector<Keyframe>> written = images.Write(dir, {Named("camera/7")});
  ASSERT_TRUE(written.ok());
  ASSERT_EQ(written->size(), 1u);
  EXPECT_TRUE(fs::exists(ColorImagePath(dir, "camera/7")));
  EXPECT_FALSE(fs::exists(ColorImagePath(dir, "recent")));  // not a keyframe: not written
}

TEST(KeyframeImagesTest, AnUnwritableFolderIsAnErrorNamingIt) {
  KeyframeImages images;
  images.AddFrameImage("frames/000001", Image(1));
  const fs::path file = fs::path(testing::TempDir()) / "keyframe_images_not_a_folder";
  fs::remove_all(file);
  std::ofstream(file) << "not a folder";
  const Result<std::vector<Keyframe>> written = images.Write(file, {Named("frames/000001")});
  ASSERT_FALSE(written.ok());
  EXPECT_NE(written.status().message().find(file.string()), std::string::npos);
}

}  // namespace
}  // namespace semchain::semantic
