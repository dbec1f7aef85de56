#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "mapping/distance_field.h"

// The distance field as, per cell, the number of its distance among the field's distinct
// distances. An exact Euclidean distance transform capped at laser_likelihood_max_dist has only
// a few thousand distinct values (square roots of integer squared cell distances), so the
// likelihood-field model can evaluate exp(−d² / 2σ²) once per distinct distance instead of once
// per beam, and a look-up reads 2 bytes instead of 4. The look-up is the DistanceField's own
// (same cell, same distance, max_distance off the map), so the weights stay bit for bit the same.
namespace semchain::localization {

class QuantizedDistanceField {
 public:
  explicit QuantizedDistanceField(const mapping::DistanceField& field);

  // False when the field has more distinct distances than 16-bit numbers can name (then the
  // model evaluates the field directly).
  bool ok() const { return ok_; }
  // The distinct distances (metres, as DistanceField::DistanceAtCell returns them); the last is
  // the distance off the map.
  const std::vector<double>& distances() const { return distances_; }
  int off_map() const { return static_cast<int>(distances_.size()) - 1; }
  // The number of the distance of cell (x, y), which must lie on the map.
  int At(int x, int y) const { return classes_[static_cast<std::size_t>(y) * width_ + x]; }
  // The same by the row-major index y · width + x.
  int AtIndex(int index) const { return classes_[static_cast<std::size_t>(index)]; }
  // The number of the distance of cell (x, y), off_map() off the map.
  int ClassOfCell(int x, int y) const {
    return static_cast<unsigned>(x) < static_cast<unsigned>(width_) &&
                   static_cast<unsigned>(y) < static_cast<unsigned>(height_)
               ? At(x, y)
               : off_map();
  }
  // The number of the distance at the point 'dx', 'dy' metres from the map origin: of the cell
  // DistanceField::CellOf finds (floor of the quotient by the resolution), off_map() off it.
  int ClassAt(double dx, double dy) const {
    return ClassOfCell(FloorOfQuotient(dx), FloorOfQuotient(dy));
  }
  double inverse_resolution() const { return inverse_resolution_; }

  // FloorOfQuotient trusts the product when its fraction is at least this far from a cell
  // border (the product is within a few ulps, < 1e-9 cells, of the quotient) and its magnitude
  // below kMaxQuotient cells.
  static constexpr double kBorderGuard = 1e-6;
  static constexpr double kMaxQuotient = 1e9;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  // floor(a / resolution) as DistanceField::CellOf computes it, by a product with the inverse
  // (a division costs as much as the rest of a beam): the product is within an ulp or two of the
  // quotient, so the floors can differ only when it lies within a hair of an integer, and then
  // the division decides. -1 (off the map) beyond int range.
  int FloorOfQuotient(double a) const {
    const double q = a * inverse_resolution_;
    if (!(std::abs(q) < kMaxQuotient)) return -1;
    int i = static_cast<int>(q);
    i -= q < i ? 1 : 0;
    const double fraction = q - i;
    if (fraction < kBorderGuard || fraction > 1.0 - kBorderGuard) {
      return static_cast<int>(std::floor(a / resolution_));
    }
    return i;
  }

  bool ok_ = false;
  double resolution_ = 0.0;
  double inverse_resolution_ = 0.0;
  int width_ = 0;
  int height_ = 0;
  std::vector<double> distances_;
  std::vector<std::uint16_t> classes_;  // row-major as the field
};

}  // namespace semchain::localization
