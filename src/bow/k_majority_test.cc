#include "bow/k_majority.h"

#include <gtest/gtest.h>

#include <set>

#include "bow/bow_testing.h"

namespace semchain::bow {
namespace {

using testing::Filled;

// 'centre' with bits 'first' and 'first' + 1 flipped.
cv::Mat Flipped(const cv::Mat& centre, int first) {
  cv::Mat d = centre.clone();
  for (int bit : {first, first + 1}) d.at<unsigned char>(0, bit / 8) ^= (1 << (bit % 8));
  return d;
}

TEST(KMajorityTest, HammingDistanceCountsDifferentBits) {
  EXPECT_EQ(HammingDistance(Filled(0x00).ptr(), Filled(0xFF).ptr(), 32), 256);
  EXPECT_EQ(HammingDistance(Filled(0x0F).ptr(), Filled(0xFF).ptr(), 32), 128);
  EXPECT_EQ(HammingDistance(Filled(0x0F).ptr(), Flipped(Filled(0x0F), 10).ptr(), 32), 2);
}

TEST(KMajorityTest, MajorityDescriptorSetsBitsOfMoreThanHalf) {
  cv::Mat rows;
  rows.push_back(Filled(0b00000111));
  rows.push_back(Filled(0b00000011));
  rows.push_back(Filled(0b00000001));
  // Bit 0 in 3 of 3, bit 1 in 2 of 3, bit 2 in 1 of 3.
  EXPECT_EQ(cv::norm(MajorityDescriptor(rows, {0, 1, 2}), Filled(0b00000011), cv::NORM_HAMMING),
            0.0);
  // Two rows: bit 1 is a tie (1 of 2) and stays clear.
  EXPECT_EQ(cv::norm(MajorityDescriptor(rows, {0, 2}), Filled(0b00000001), cv::NORM_HAMMING), 0.0);
}

// Three known centres, five members each with two of their bits flipped (different bits per
// member): k-majority finds the three groups and their majorities are the centres exactly.
TEST(KMajorityTest, RecoversKnownClustersAndMajorityCentres) {
  const std::vector<cv::Mat> centres = {Filled(0x00), Filled(0xFF), Filled(0x0F)};
  cv::Mat descriptors;
  std::vector<int> truth;
  for (int member = 0; member < 5; ++member) {
    for (int c = 0; c < 3; ++c) {
      descriptors.push_back(Flipped(centres[c], 40 * member + 3 * c));
      truth.push_back(c);
    }
  }
  std::vector<int> rows(static_cast<std::size_t>(descriptors.rows));
  for (int i = 0; i < descriptors.rows; ++i) rows[i] = i;
  KMajorityOptions options;
  options.k = 3;
  Rng rng = MakeRng(7);
  const KMajorityResult result = KMajority(descriptors, rows, options, rng);
  ASSERT_EQ(result.centers.rows, 3);
  // Same cluster ⇔ same true centre, and each found centre is a true centre bit for bit.
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (std::size_t j = 0; j < rows.size(); ++j) {
      EXPECT_EQ(result.assignment[i] == result.assignment[j], truth[i] == truth[j]);
    }
    const cv::Mat found = result.centers.row(result.assignment[i]);
    EXPECT_EQ(cv::norm(found, centres[truth[i]], cv::NORM_HAMMING), 0.0) << "row " << i;
  }
}

TEST(KMajorityTest, FewRowsAreTheirOwnClustersAndDuplicatesShareOne) {
  cv::Mat descriptors;
  descriptors.push_back(Filled(0x01));
  descriptors.push_back(Filled(0x02));
  descriptors.push_back(Filled(0x01));
  KMajorityOptions options;
  options.k = 4;
  Rng rng = MakeRng(1);
  const KMajorityResult result = KMajority(descriptors, {0, 1, 2}, options, rng);
  EXPECT_EQ(result.centers.rows, 2);
  EXPECT_EQ(result.assignment, (std::vector<int>{0, 1, 0}));
}

TEST(KMajorityTest, SameSeedSameClusters) {
  cv::Mat descriptors(200, 32, CV_8UC1);
  Rng fill = MakeRng(3);
  for (int r = 0; r < descriptors.rows; ++r) {
    for (int c = 0; c < 32; ++c)
      descriptors.at<unsigned char>(r, c) = static_cast<unsigned char>(fill());
  }
  std::vector<int> rows(200);
  for (int i = 0; i < 200; ++i) rows[i] = i;
  Rng a = MakeRng(5);
  Rng b = MakeRng(5);
  const KMajorityResult first = KMajority(descriptors, rows, {}, a);
  const KMajorityResult second = KMajority(descriptors, rows, {}, b);
  EXPECT_EQ(first.assignment, second.assignment);
  EXPECT_EQ(cv::norm(first.centers, second.centers, cv::NORM_HAMMING), 0.0);
}

}  // namespace
}  // namespace semchain::bow
