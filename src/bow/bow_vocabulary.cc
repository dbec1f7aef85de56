#include "bow/bow_vocabulary.h"

#include <cmath>
#include <limits>

#include "bow/k_majority.h"
#include "core/check.h"

namespace semchain::bow {

bool VocabularyOptions::Validate(std::string* error) const {
  if (branching < 2 || branching > 64) {
    *error = "k (branching) must be in [2, 64], got " + std::to_string(branching);
    return false;
  }
  if (levels < 1 || levels > 8) {
    *error = "levels must be in [1, 8], got " + std::to_string(levels);
    return false;
  }
  if (max_iterations < 1) {
    *error = "max_iterations must be at least 1";
    return false;
  }
  return true;
}

Result<Vocabulary> Vocabulary::FromData(VocabularyData data) {
  const std::size_t n = data.parent.size();
  const auto bad = [](const std::string& what) { return Status::Error("vocabulary: " + what); };
  if (data.branching < 2 || data.levels < 1) return bad("bad k or L");
  if (n == 0 || data.parent[0] != -1) return bad("no root node");
  if (data.word.size() != n || data.weight.size() != n ||
      data.descriptors.rows != static_cast<int>(n) ||
      data.descriptors.cols != kOrbDescriptorBytes || data.descriptors.type() != CV_8UC1) {
    return bad("node arrays of different lengths");
  }
  Vocabulary vocabulary;
  vocabulary.children_.resize(n);
  vocabulary.depth_.assign(n, 0);
  for (std::size_t i = 1; i < n; ++i) {
    const int p = data.parent[i];
    if (p < 0 || static_cast<std::size_t>(p) >= i) {
      return bad("node " + std::to_string(i) + ": parent " + std::to_string(p) +
                 " does not come before it");
    }
    vocabulary.children_[p].push_back(static_cast<int>(i));
    vocabulary.depth_[i] = vocabulary.depth_[p] + 1;
    if (vocabulary.depth_[i] > data.levels) return bad("deeper than L");
    if (static_cast<int>(vocabulary.children_[p].size()) > data.branching) {
      return bad("node " + std::to_string(p) + " has more than k children");
    }
  }
  std::vector<int> leaf_of_word(n, -1);
  std::size_t words = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const bool leaf = vocabulary.children_[i].empty();
    const WordId w = data.word[i];
    if (!std::isfinite(data.weight[i]) || data.weight[i] < 0.0) return bad("bad weight");
    if (leaf != (w >= 0) || w >= static_cast<int>(n) || (w >= 0 && leaf_of_word[w] >= 0)) {
      return bad("node " + std::to_string(i) + ": bad word id " + std::to_string(w));
    }
    if (w >= 0) {
      leaf_of_word[w] = static_cast<int>(i);
      ++words;
    }
  }
  if (n > 1 && vocabulary.children_[0].empty()) return bad("a root without children");
  leaf_of_word.resize(words);
  for (int leaf : leaf_of_word) {
    if (leaf < 0) return bad("word ids are not 0..W-1");
  }
  vocabulary.leaf_of_word_ = std::move(leaf_of_word);
  vocabulary.data_ = std::move(data);
  return vocabulary;
}

WordId Vocabulary::Word(const unsigned char* descriptor) const {
  int node = 0;
  while (!children_[node].empty()) {
    int best = children_[node].front();
    int best_distance = std::numeric_limits<int>::max();
    for (int child : children_[node]) {
      const int d = HammingDistance(data_.descriptors.ptr<unsigned char>(child), descriptor,
                                    kOrbDescriptorBytes);
      if (d < best_distance) {
        best = child;
        best_distance = d;
      }
    }
    node = best;
  }
  return data_.word[node];
}

BowVector Vocabulary::Transform(const cv::Mat& descriptors) const {
  return Transform(descriptors, 0, nullptr);
}

BowVector Vocabulary::Transform(const cv::Mat& descriptors, int level,
                                FeatureVector* features) const {
  SEMCHAIN_CHECK(!empty());
  if (descriptors.empty()) return {};
  SEMCHAIN_CHECK(descriptors.type() == CV_8UC1 && descriptors.cols == kOrbDescriptorBytes);
  BowAccumulator accumulator;
  for (int row = 0; row < descriptors.rows; ++row) {
    const unsigned char* d = descriptors.ptr<unsigned char>(row);
    const WordId word = Word(d);
    // The term frequency's 1/n_I is common to all words and vanishes in the normalisation.
    accumulator.Add(word, Weight(word));
    if (features == nullptr) continue;
    int node = leaf_of_word_[word];
    while (depth_[node] > level) node = data_.parent[node];
    (*features)[node].push_back(row);
  }
  return accumulator.Finalize();
}

}  // namespace semchain::bow
