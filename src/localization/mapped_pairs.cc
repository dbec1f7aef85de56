#include "localization/mapped_pairs.h"

namespace semchain::localization {
namespace {

// Mapped pairs farther apart than this are never seen together by a camera of a few metres'
// range; not indexing them keeps the index small on large maps.
constexpr double kMaxPairDistance = 15.0;

}  // namespace

MappedPairs::MappedPairs(const std::vector<semantic::SemanticObject>& objects,
                         double distance_tolerance)
    : distance_tolerance_(distance_tolerance) {
  for (const semantic::SemanticObject& object : objects) class_id_.emplace(object.class_name, 0);
  int next_id = 0;
  for (auto& [name, id] : class_id_) id = next_id++;  // name order
  const std::size_t classes = class_id_.size();
  objects_of_class_.resize(classes);
  pairs_.resize(classes * classes);
  std::vector<int> class_of;
  for (std::size_t o = 0; o < objects.size(); ++o) {
    class_of.push_back(class_id_.at(objects[o].class_name));
    objects_of_class_[static_cast<std::size_t>(class_of.back())].push_back(static_cast<int>(o));
  }
  for (std::size_t a = 0; a < objects.size(); ++a) {
    for (std::size_t b = 0; b < objects.size(); ++b) {
      if (a == b) continue;
      const int ca = class_of[a];
      const int cb = class_of[b];
      // Each unordered pair once, under its classes in id order (a first when equal).
      if (ca > cb || (ca == cb && a > b)) continue;
      const double distance = (objects[a].center - objects[b].center).norm();
      if (distance > kMaxPairDistance) continue;
      pairs_[static_cast<std::size_t>(ca) * classes + static_cast<std::size_t>(cb)].push_back(
          {distance, static_cast<int>(a), static_cast<int>(b)});
    }
  }
  for (std::vector<IndexedPair>& list : pairs_) {
    std::sort(list.begin(), list.end(),
              [](const IndexedPair& x, const IndexedPair& y) { return x.distance < y.distance; });
  }
}

int MappedPairs::ClassId(const std::string& class_name) const {
  const auto it = class_id_.find(class_name);
  return it == class_id_.end() ? -1 : it->second;
}

}  // namespace semchain::localization
