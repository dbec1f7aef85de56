#include "bow/bow_database.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"

namespace semchain::bow {

BowDatabase::BowDatabase(int words, int direct_index_level)
    : direct_index_level_(direct_index_level), inverted_(static_cast<std::size_t>(words)) {
  SEMCHAIN_CHECK(words >= 0);
}

int BowDatabase::Add(BowVector vector, FeatureVector features) {
  L1Normalize(&vector);
  const int entry = size();
  for (const auto& [word, weight] : vector) {
    SEMCHAIN_CHECK(word >= 0 && word < static_cast<int>(inverted_.size()));
    inverted_[word].emplace_back(entry, weight);
  }
  vectors_.push_back(std::move(vector));
  features_.push_back(std::move(features));
  return entry;
}

std::vector<BowMatch> BowDatabase::Query(const BowVector& query, int max_results) const {
  BowVector q = query;
  L1Normalize(&q);
  // With unit L1 norms, s = ½ Σ_common (|a| + |b| − |a − b|) (bow_vector.cc): accumulate the
  // shared words' terms through the inverted index.
  std::vector<double> sum(vectors_.size(), 0.0);
  for (const auto& [word, a] : q) {
    if (word < 0 || word >= static_cast<int>(inverted_.size())) continue;
    for (const auto& [entry, b] : inverted_[word]) sum[entry] += a + b - std::abs(a - b);
  }
  std::vector<BowMatch> matches;
  for (std::size_t entry = 0; entry < sum.size(); ++entry) {
    if (sum[entry] > 0.0) matches.push_back({static_cast<int>(entry), 0.5 * sum[entry]});
  }
  const auto better = [](const BowMatch& x, const BowMatch& y) {
    return x.score > y.score || (x.score == y.score && x.entry < y.entry);
  };
  const std::size_t n =
      std::min(matches.size(), static_cast<std::size_t>(std::max(0, max_results)));
  std::partial_sort(matches.begin(), matches.begin() + static_cast<long>(n), matches.end(), better);
  matches.resize(n);
  return matches;
}

}  // namespace semchain::bow
