#include "bow/bow_vocabulary.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "bow/bow_testing.h"

namespace semchain::bow {
namespace {

using testing::Filled;
using testing::RandomDescriptors;
using testing::Stack;

// Three distinct descriptors d0, d1, d2 in three training images A = {d0, d0, d1}, B = {d1},
// C = {d2}; with k = 3 and L = 1 each is a word. IDF: d0 in 1 of 3 images → log 3, d1 in 2 →
// log 1.5, d2 in 1 → log 3.
class ToyVocabularyTest : public ::testing::Test {
 protected:
  void SetUp() override {
    images_ = {Stack({d0_, d0_, d1_}), Stack({d1_}), Stack({d2_})};
    VocabularyOptions options;
    options.branching = 3;
    options.levels = 1;
    Result<Vocabulary> trained = Vocabulary::Train(images_, options);
    ASSERT_TRUE(trained.ok()) << trained.status().message();
    vocabulary_ = *trained;
  }

  cv::Mat d0_ = Filled(0x00), d1_ = Filled(0xFF), d2_ = Filled(0x0F);
  std::vector<cv::Mat> images_;
  Vocabulary vocabulary_;
};

TEST_F(ToyVocabularyTest, EachDistinctDescriptorIsAWordWithItsIdf) {
  ASSERT_EQ(vocabulary_.words(), 3);
  const WordId w0 = vocabulary_.Word(d0_.ptr()), w1 = vocabulary_.Word(d1_.ptr()),
               w2 = vocabulary_.Word(d2_.ptr());
  EXPECT_EQ(std::set<WordId>({w0, w1, w2}).size(), 3u);
  EXPECT_NEAR(vocabulary_.Weight(w0), std::log(3.0), 1e-12);
  EXPECT_NEAR(vocabulary_.Weight(w1), std::log(1.5), 1e-12);
  EXPECT_NEAR(vocabulary_.Weight(w2), std::log(3.0), 1e-12);
}

TEST_F(ToyVocabularyTest, TfIdfOfImageA) {
  // tf: d0 2/3, d1 1/3; tf·idf = (2/3 · 1.098612, 1/3 · 0.405465) → L1-normalised
  // (2.197225, 0.405465) / 2.602690 = (0.844213, 0.155787).
  const BowVector v = vocabulary_.Transform(images_[0]);
  ASSERT_EQ(v.size(), 2u);
  const WordId w0 = vocabulary_.Word(d0_.ptr());
  for (const auto& [word, weight] : v) {
    EXPECT_NEAR(weight, word == w0 ? 0.844213 : 0.155787, 1e-6);
  }
  // Image C is a single word: weight 1 after normalisation; A and C share no word.
  const BowVector c = vocabulary_.Transform(images_[2]);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_DOUBLE_EQ(c[0].second, 1.0);
  EXPECT_DOUBLE_EQ(L1Score(v, c), 0.0);
}

TEST_F(ToyVocabularyTest, DirectIndexGroupsFeaturesByNode) {
  FeatureVector features;
  vocabulary_.Transform(images_[0], 1, &features);
  ASSERT_EQ(features.size(), 2u);  // the two d0 features share a node, d1 has its own
  std::multiset<std::size_t> sizes;
  for (const auto& [node, indices] : features) sizes.insert(indices.size());
  EXPECT_EQ(sizes, (std::multiset<std::size_t>{1, 2}));
}

// A file can pass its checksum and still describe a broken tree (written by another program):
// FromData refuses it with a message instead of descending into garbage.
TEST_F(ToyVocabularyTest, FromDataRefusesBrokenTrees) {
  VocabularyData forward = vocabulary_.data();
  forward.parent[1] = 3;
  const Result<Vocabulary> a = Vocabulary::FromData(forward);
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.status().message().find("does not come before it"), std::string::npos);
  VocabularyData duplicate = vocabulary_.data();
  duplicate.word[2] = duplicate.word[1];
  EXPECT_FALSE(Vocabulary::FromData(duplicate).ok());
  VocabularyData inner_word = vocabulary_.data();
  inner_word.word[0] = 0;  // the root has children: it cannot be a word
  EXPECT_FALSE(Vocabulary::FromData(inner_word).ok());
  VocabularyData negative = vocabulary_.data();
  negative.weight[1] = -1.0;
  EXPECT_FALSE(Vocabulary::FromData(negative).ok());
  EXPECT_TRUE(Vocabulary::FromData(vocabulary_.data()).ok());
}

TEST(VocabularyTest, TreeRespectsKAndLAndIsReproducible) {
  std::vector<cv::Mat> images;
  for (int i = 0; i < 20; ++i)
    images.push_back(RandomDescriptors(100, static_cast<std::uint64_t>(i)));
  VocabularyOptions options;
  options.branching = 5;
  options.levels = 3;
  options.seed = 9;
  const Result<Vocabulary> a = Vocabulary::Train(images, options);
  const Result<Vocabulary> b = Vocabulary::Train(images, options);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_LE(a->words(), 125);
  EXPECT_GT(a->words(), 100);  // 2000 descriptors fill almost every leaf of 5³
  EXPECT_EQ(a->data().parent, b->data().parent);
  EXPECT_EQ(cv::norm(a->data().descriptors, b->data().descriptors, cv::NORM_HAMMING), 0.0);
  // A training image is most similar to itself.
  const BowVector v3 = a->Transform(images[3]);
  EXPECT_NEAR(L1Score(v3, a->Transform(images[3])), 1.0, 1e-12);
  EXPECT_LT(L1Score(v3, a->Transform(images[4])), 0.5);
}

TEST(VocabularyTest, BadOptionsAndTooFewDescriptorsAreErrors) {
  VocabularyOptions options;
  options.branching = 1;
  EXPECT_FALSE(Vocabulary::Train({RandomDescriptors(50, 1)}, options).ok());
  const Result<Vocabulary> few = Vocabulary::Train({RandomDescriptors(3, 1)}, VocabularyOptions());
  ASSERT_FALSE(few.ok());
  EXPECT_NE(few.status().message().find("too few"), std::string::npos);
}

}  // namespace
}  // namespace semchain::bow
