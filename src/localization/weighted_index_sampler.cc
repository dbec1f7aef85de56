#include "localization/weighted_index_sampler.h"

#include <algorithm>
#include <numeric>

#include "core/check.h"

namespace semchain::localization {

WeightedIndexSampler::WeightedIndexSampler(const std::vector<double>& weights)
    : cumulative_(weights.size()), guide_(weights.size()) {
  SEMCHAIN_CHECK(!weights.empty());
  std::partial_sum(weights.begin(), weights.end(), cumulative_.begin());
  SEMCHAIN_CHECK(cumulative_.back() > 0.0);
  const std::size_t n = weights.size();
  slices_per_unit_ = static_cast<double>(n) / cumulative_.back();
  // Slice j holds the r with floor(r · n / total) = j, so r >= j / slices_per_unit up to a few
  // ulps; its guide is the first index whose sum exceeds a bound a little below that, so no
  // index before the guide can answer an r of the slice.
  const double slack = 1e-9 * cumulative_.back();
  std::size_t i = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const double lower = static_cast<double>(j) / slices_per_unit_ - slack;
    while (i + 1 < n && cumulative_[i] <= lower) ++i;
    guide_[j] = i;
  }
}

std::size_t WeightedIndexSampler::IndexOf(double r) const {
  const std::size_t n = cumulative_.size();
  const double slice = r * slices_per_unit_;
  std::size_t i = slice > 0.0 ? guide_[std::min(n - 1, static_cast<std::size_t>(slice))] : 0;
  while (i + 1 < n && cumulative_[i] <= r) ++i;
  return i;
}

std::vector<std::size_t> SystematicDraws(const WeightedIndexSampler& sampler, std::size_t count,
                                         double offset) {
  SEMCHAIN_CHECK(offset >= 0.0 && offset < 1.0);
  std::vector<std::size_t> draws(count);
  const double spacing = sampler.total() / static_cast<double>(count);
  for (std::size_t k = 0; k < count; ++k) {
    draws[k] = sampler.IndexOf((offset + static_cast<double>(k)) * spacing);
  }
  return draws;
}

}  // namespace semchain::localization
