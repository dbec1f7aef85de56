#pragma once

#include <utility>
#include <vector>

// Bag-of-words vectors (seed 000 §3.1 step 3; Gálvez-López and Tardós 2012, DBoW2): sparse
// word → weight lists and their L1 similarity score.
namespace semchain::bow {

using WordId = int;

// Sorted by word id, each word once, weights > 0. Sparse because an image holds a few hundred
// of the vocabulary's thousands of words.
using BowVector = std::vector<std::pair<WordId, double>>;

// Adds 'weight' to 'word' of an unsorted accumulation; Finalize() sorts and merges.
class BowAccumulator {
 public:
  void Add(WordId word, double weight) { entries_.emplace_back(word, weight); }
  // The summed weights per word, sorted by word id, zero weights dropped, L1-normalised (an
  // empty vector when nothing positive was added).
  BowVector Finalize();

 private:
  BowVector entries_;
};

// Scales 'vector' to unit L1 norm (unchanged when its norm is zero).
void L1Normalize(BowVector* vector);

// The L1 score s(v1, v2) = 1 − ½ |v1/|v1| − v2/|v2||₁ (DBoW2): 1 for identical directions, 0 for
// vectors without a common word. Vectors need not be normalised; an empty one scores 0.
double L1Score(const BowVector& v1, const BowVector& v2);

}  // namespace semchain::bow
