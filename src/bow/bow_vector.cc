#include "bow/bow_vector.h"

#include <algorithm>
#include <cmath>

namespace semchain::bow {
namespace {

double L1Norm(const BowVector& vector) {
  double norm = 0.0;
  for (const auto& [word, weight] : vector) norm += std::abs(weight);
  return norm;
}

}  // namespace

BowVector BowAccumulator::Finalize() {
  std::sort(entries_.begin(), entries_.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  BowVector merged;
  for (const auto& [word, weight] : entries_) {
    if (!merged.empty() && merged.back().first == word) {
      merged.back().second += weight;
    } else {
      merged.emplace_back(word, weight);
    }
  }
  std::erase_if(merged, [](const auto& entry) { return !(entry.second > 0.0); });
  L1Normalize(&merged);
  entries_.clear();
  return merged;
}

void L1Normalize(BowVector* vector) {
  const double norm = L1Norm(*vector);
  if (norm <= 0.0) return;
  for (auto& entry : *vector) entry.second /= norm;
}

double L1Score(const BowVector& v1, const BowVector& v2) {
  const double n1 = L1Norm(v1);
  const double n2 = L1Norm(v2);
  if (n1 <= 0.0 || n2 <= 0.0) return 0.0;
  // |a − b| summed over all words = |a|₁ + |b|₁ − Σ_common (|a| + |b| − |a − b|), and both
  // norms are 1, so only the words the two vectors share need visiting.
  double common = 0.0;
  auto a = v1.begin();
  auto b = v2.begin();
  while (a != v1.end() && b != v2.end()) {
    if (a->first < b->first) {
      ++a;
    } else if (b->first < a->first) {
      ++b;
    } else {
      const double x = a->second / n1;
      const double y = b->second / n2;
      common += std::abs(x) + std::abs(y) - std::abs(x - y);
      ++a;
      ++b;
    }
  }
  return std::clamp(0.5 * common, 0.0, 1.0);
}

}  // namespace semchain::bow
