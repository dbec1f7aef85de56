#pragma once

#include <cstdint>

#include "core/pose2.h"
#include "localization/key_index.h"

// KLD sampling (Fox, "Adapting the sample size in particle filters through KLD-sampling",
// IJRR 2003, eq. 13): the number of samples that keeps the Kullback-Leibler distance between the
// sample-based and the true posterior below ε with probability 1 − δ, when the samples fall into
// k histogram bins, using the Wilson-Hilferty approximation of the χ² quantile:
//   n = (k − 1) / (2ε) · {1 − 2 / (9(k − 1)) + sqrt(2 / (9(k − 1))) z_{1−δ}}³.
namespace semchain::localization {

// The bound for 'k' occupied bins, error 'epsilon' and standard normal quantile 'z'; 0 for
// k <= 1 (any number of samples represents one bin).
double KldSampleBound(int k, double epsilon, double z);

// The set of occupied (x, y, θ) histogram bins of a sample set.
class PoseBins {
 public:
  PoseBins(double bin_x, double bin_y, double bin_theta)
      : bin_x_(bin_x), bin_y_(bin_y), bin_theta_(bin_theta) {}
  // Adds the bin of 'pose'; returns true when it was empty.
  bool Insert(const Pose2& pose);
  int count() const { return bins_.size(); }
  // Empties the set, keeping room for 'expected' bins.
  void Clear(std::size_t expected = 0) { bins_.Clear(expected); }

 private:
  double bin_x_, bin_y_, bin_theta_;
  KeyIndex bins_;
};

}  // namespace semchain::localization
