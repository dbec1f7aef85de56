#pragma once

#include <algorithm>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "semantic/semantic_map.h"

// Chain retrieval (seed 001 §2.1): the pairs of mapped objects indexed by their classes and
// sorted by distance, so that the pairs of two classes whose distance D explains an observed
// distance d ((1 − α)D < d < (1 + α)D) are a binary search away.
namespace semchain::localization {

class MappedPairs {
 public:
  // Indexes the pairs of 'objects' that a camera may see together; 'distance_tolerance' is α.
  MappedPairs(const std::vector<semantic::SemanticObject>& objects, double distance_tolerance);

  // The class id of 'class_name' (-1: a class the map does not have). Classes are numbered in
  // name order, so that a pair's classes in id order are in name order.
  int ClassId(const std::string& class_name) const;
  // The objects of class id 'class_id' (indices into the constructor's 'objects').
  const std::vector<int>& ObjectsOfClass(int class_id) const {
    return objects_of_class_[static_cast<std::size_t>(class_id)];
  }

  // Calls visit(a, b, D) for every mapped pair (a of class_a, b of class_b; indices into the
  // constructor's 'objects') whose distance D satisfies the retrieval tolerance for the observed
  // distance d missing by up to 'slack' metres first. Unknown classes (-1) visit nothing.
  template <typename Visit>
  void ForEachPair(int class_a, int class_b, double d, double slack, Visit&& visit) const;

 private:
  struct IndexedPair {
    double distance;
    int a;  // indices into the constructor's 'objects'
    int b;
  };

  std::map<std::string, int> class_id_;
  std::vector<std::vector<int>> objects_of_class_;  // by class id
  // Mapped pairs by classes (a, b), a <= b, at a * classes + b; sorted by distance.
  std::vector<std::vector<IndexedPair>> pairs_;
  double distance_tolerance_;
};

template <typename Visit>
void MappedPairs::ForEachPair(int class_a, int class_b, double d, double slack,
                              Visit&& visit) const {
  if (class_a < 0 || class_b < 0) return;
  const bool swapped = class_a > class_b;
  const std::vector<IndexedPair>& list =
      pairs_[static_cast<std::size_t>(std::min(class_a, class_b)) * class_id_.size() +
             static_cast<std::size_t>(std::max(class_a, class_b))];
  const double low = std::max(0.0, d - slack) / (1.0 + distance_tolerance_);
  const double high = (d + slack) / (1.0 - distance_tolerance_);
  auto first =
      std::upper_bound(list.begin(), list.end(), low,
                       [](double value, const IndexedPair& p) { return value < p.distance; });
  for (; first != list.end() && first->distance < high; ++first) {
    if (swapped) {
      visit(first->b, first->a, first->distance);
    } else {
      visit(first->a, first->b, first->distance);
    }
    // Same classes: either object may be the first one seen.
    if (class_a == class_b) visit(first->b, first->a, first->distance);
  }
}

}  // namespace semchain::localization
