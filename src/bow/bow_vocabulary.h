#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "bow/bow_vector.h"
#include "core/status.h"

// The hierarchical visual vocabulary of seed 000 §3.1 step 1 (DESIGN.md §3.7; the vocabulary
// tree of Nistér and Stewénius 2006 as DBoW2 builds it for binary descriptors): ORB descriptors
// clustered by k-majority into a tree of branching factor k and depth L; the leaves are the
// words, each weighted by its inverse document frequency over the training images.
namespace semchain::bow {

// ORB's rBRIEF descriptor: 256 bits.
inline constexpr int kOrbDescriptorBytes = 32;

struct VocabularyOptions {
  int branching = 10;  // k: children per node
  // L: depth of the tree (the root is level 0, words at most at level L). k^L = 10 000 words
  // suits a few hundred training images of a few hundred features each; a node with fewer
  // descriptors than k is split into its distinct descriptors and stops there.
  int levels = 4;
  std::uint64_t seed = 0;   // k-means++ seeding draws (MakeRng(seed, 0))
  int max_iterations = 20;  // k-majority rounds per node
  bool Validate(std::string* error) const;
};

// The tree as plain arrays, node 0 the root and every parent before its children (the
// serialised form; see bow_vocabulary_io.h).
struct VocabularyData {
  int branching = 0;
  int levels = 0;
  int training_images = 0;     // N of the IDF weights
  std::vector<int> parent;     // per node; -1 for the root
  std::vector<WordId> word;    // per node; -1 for inner nodes, 0..W−1 for leaves
  std::vector<double> weight;  // per node; IDF log(N / n_i) of a leaf, 0 for inner nodes
  cv::Mat descriptors;         // CV_8UC1, one row per node (the root's is zeros)
};

// Node ids at one level of the tree → the indices of the features that passed through them
// (DBoW2's direct index): features under the same node are the candidates for matching.
using FeatureVector = std::map<int, std::vector<int>>;

class Vocabulary {
 public:
  Vocabulary() = default;

  // Trains on the descriptors of each training image (CV_8UC1, kOrbDescriptorBytes per row;
  // images without features are allowed but count in N). Each node is split by k-majority
  // (k_majority.h) down to options.levels; the IDF weight of word i is log(N / n_i) with n_i
  // the training images in which word i occurs (a word no image reaches counts as n_i = 1).
  // 'progress' (may be empty) gets (done, total): one step per subtree under the root, then
  // the IDF pass.
  static Result<Vocabulary> Train(
      const std::vector<cv::Mat>& images, const VocabularyOptions& options,
      const std::function<void(std::size_t, std::size_t)>& progress = {});

  // Checks a tree's structure (parents first, leaves and only leaves carry words 0..W−1 once
  // each, at most 'branching' children, depth at most 'levels', finite non-negative weights).
  static Result<Vocabulary> FromData(VocabularyData data);

  // The word of one descriptor: from the root, always into the nearest child (Hamming).
  WordId Word(const unsigned char* descriptor) const;

  // The TF-IDF vector of an image's descriptors: word i gets (n_iI / n_I) · idf_i, where n_iI
  // counts the image's descriptors with that word among its n_I, then the vector is
  // L1-normalised; words weighted 0 (in every training image) are left out.
  BowVector Transform(const cv::Mat& descriptors) const;
  // The same, and the direct index: each feature under its ancestor at 'level' (1..levels;
  // a word above that level stands for itself).
  BowVector Transform(const cv::Mat& descriptors, int level, FeatureVector* features) const;

  int words() const { return static_cast<int>(leaf_of_word_.size()); }
  int nodes() const { return static_cast<int>(data_.parent.size()); }
  double Weight(WordId word) const { return data_.weight[leaf_of_word_[word]]; }
  int branching() const { return data_.branching; }
  int levels() const { return data_.levels; }
  bool empty() const { return leaf_of_word_.empty(); }
  const VocabularyData& data() const { return data_; }

 private:
  VocabularyData data_;
  std::vector<std::vector<int>> children_;
  std::vector<int> depth_;
  std::vector<int> leaf_of_word_;
};

}  // namespace semchain::bow
