#include "localization/quantized_distance_field.h"

#include <algorithm>
#include <bit>
#include <limits>

#include "localization/key_index.h"

namespace semchain::localization {

QuantizedDistanceField::QuantizedDistanceField(const mapping::DistanceField& field)
    : resolution_(field.resolution()),
      inverse_resolution_(1.0 / field.resolution()),
      width_(field.width()),
      height_(field.height()) {
  constexpr int kMaxClasses = std::numeric_limits<std::uint16_t>::max();
  // The distinct distances, numbered as first met, then sorted.
  KeyIndex seen;
  std::vector<double> first_met;
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const double d = field.DistanceAtCell({x, y});
      if (seen.Insert(std::bit_cast<std::uint64_t>(d)).second) first_met.push_back(d);
      if (seen.size() >= kMaxClasses) return;  // not ok: too many to name in 16 bits
    }
  }
  distances_ = first_met;
  std::sort(distances_.begin(), distances_.end());
  std::vector<std::uint16_t> rank(first_met.size());
  for (std::size_t i = 0; i < first_met.size(); ++i) {
    rank[i] = static_cast<std::uint16_t>(
        std::lower_bound(distances_.begin(), distances_.end(), first_met[i]) - distances_.begin());
  }
  classes_.resize(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_));
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const double d = field.DistanceAtCell({x, y});
      classes_[static_cast<std::size_t>(y) * width_ + x] =
          rank[static_cast<std::size_t>(seen.Find(std::bit_cast<std::uint64_t>(d)))];
    }
  }
  distances_.push_back(field.DistanceAtCell({-1, -1}));  // off the map
  ok_ = true;
}

}  // namespace semchain::localization
