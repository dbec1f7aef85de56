#pragma once

#include <string>
#include <vector>

#include "bow/bow_vector.h"
#include "bow/bow_vocabulary.h"

// The keyframe database of the bag of words (seed 000 §3.1 step 3; DBoW2's database): each
// entry's BoW vector, an inverted index word → (entry, weight) that makes a query visit only
// the entries sharing a word with it, and a direct index entry → (node at a level → feature
// indices) for later feature matching between a query and its best entry.
namespace semchain::bow {

struct BowMatch {
  int entry = -1;
  double score = 0.0;  // L1 score (bow_vector.h), 0..1
};

class BowDatabase {
 public:
  // 'words' is the vocabulary's word count; 'direct_index_level' the tree level (1..L) of the
  // direct index, as Vocabulary::Transform takes it.
  BowDatabase(int words, int direct_index_level);

  // Adds an entry and returns its id (0, 1, ... in the order added).
  int Add(BowVector vector, FeatureVector features = {});

  // The entries with the highest L1 score against 'query', best first (ties: lower id first),
  // at most 'max_results', only those with a positive score.
  std::vector<BowMatch> Query(const BowVector& query, int max_results) const;

  int size() const { return static_cast<int>(vectors_.size()); }
  int direct_index_level() const { return direct_index_level_; }
  const BowVector& vector(int entry) const { return vectors_[entry]; }
  const FeatureVector& features(int entry) const { return features_[entry]; }
  // The (entry, weight) list of 'word', in the order the entries were added.
  const std::vector<std::pair<int, double>>& postings(WordId word) const { return inverted_[word]; }

 private:
  int direct_index_level_;
  std::vector<std::vector<std::pair<int, double>>> inverted_;
  std::vector<BowVector> vectors_;
  std::vector<FeatureVector> features_;
};

}  // namespace semchain::bow
