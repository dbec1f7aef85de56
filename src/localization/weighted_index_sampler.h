#pragma once

#include <cstddef>
#include <vector>

// Draws indices in proportion to weights by inverting their cumulative sum, as
// std::upper_bound on the partial sums does (the index of the first sum above r, at most the
// last), in expected constant time per draw: a guide table (Chen & Asau 1974) of one entry per
// weight gives, for each of n equal slices of [0, total), the first index that can answer for an
// r in it, and the draw steps forward from there. Building it is linear, so KLD resampling is
// linear in the particle count instead of n log n, and it draws exactly the indices that the
// binary search drew for the same r.
namespace semchain::localization {

class WeightedIndexSampler {
 public:
  // 'weights' non-negative with a positive sum.
  explicit WeightedIndexSampler(const std::vector<double>& weights);

  double total() const { return cumulative_.back(); }
  // The first index whose partial sum exceeds 'r' (the last index when none does), for r in
  // [0, total()].
  std::size_t IndexOf(double r) const;

 private:
  std::vector<double> cumulative_;  // std::partial_sum of the weights
  std::vector<std::size_t> guide_;  // guide_[j]: no index before it answers any r of slice j
  double slices_per_unit_ = 0.0;    // n / total
};

// Systematic resampling's comb: 'count' draws at r = (offset + k) · total / count, k = 0 … count−1,
// for one offset in [0, 1). Index i is drawn ⌊c·wᵢ/W⌋ or ⌈c·wᵢ/W⌉ times (W the total), where
// independent draws give Binomial(c, wᵢ/W) times. The indices come out in ascending order.
std::vector<std::size_t> SystematicDraws(const WeightedIndexSampler& sampler, std::size_t count,
                                         double offset);

}  // namespace semchain::localization
