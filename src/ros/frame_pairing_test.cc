#include "ros/frame_pairing.h"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

namespace semchain::ros1 {
namespace {

StampedImage At(std::int64_t stamp_ns) { return {stamp_ns, cv::Mat(1, 1, CV_8UC1)}; }

TEST(FramePairingTest, PairsByStampAndDropsWhatHasNoPartner) {
  std::vector<std::pair<std::int64_t, std::int64_t>> pairs;
  FramePairer pairer(10, [&pairs](StampedImage color, StampedImage depth) {
    pairs.emplace_back(color.stamp_ns, depth.stamp_ns);
    return Status::Ok();
  });
  // The depth stream misses 200 and has an extra image at 250; colour misses 400.
  ASSERT_TRUE(pairer.AddColor(At(100)).ok());
  ASSERT_TRUE(pairer.AddDepth(At(105)).ok());
  ASSERT_TRUE(pairer.AddColor(At(200)).ok());
  ASSERT_TRUE(pairer.AddDepth(At(250)).ok());
  ASSERT_TRUE(pairer.AddColor(At(300)).ok());
  ASSERT_TRUE(pairer.AddDepth(At(300)).ok());
  ASSERT_TRUE(pairer.AddDepth(At(400)).ok());
  ASSERT_TRUE(pairer.AddDepth(At(500)).ok());
  ASSERT_TRUE(pairer.AddColor(At(500)).ok());
  pairer.Finish();
  EXPECT_EQ(pairs, (std::vector<std::pair<std::int64_t, std::int64_t>>{
                       {100, 105}, {300, 300}, {500, 500}}));
  EXPECT_EQ(pairer.unpaired_color(), 1u);
  EXPECT_EQ(pairer.unpaired_depth(), 2u);
}

TEST(FramePairingTest, ASinkErrorStopsThePairing) {
  FramePairer pairer(0, [](StampedImage, StampedImage) { return Status::Error("disk full"); });
  ASSERT_TRUE(pairer.AddColor(At(1)).ok());
  EXPECT_EQ(pairer.AddDepth(At(1)).message(), "disk full");
}

}  // namespace
}  // namespace semchain::ros1
