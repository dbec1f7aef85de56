#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/pose2.h"
#include "core/rng.h"
#include "localization/quantized_distance_field.h"
#include "mapping/distance_field.h"
#include "mapping/map_io.h"

// What AMCL needs of a map_server map, computed once: the cell states, the free cells (global
// initialisation and recovery draw from them), the distance field of the likelihood-field model
// and ray casting for the beam model (nav2 amcl's map_t, occ_dist and map_calc_range).
namespace semchain::localization {

class LocalizationMap {
 public:
  // 'likelihood_max_dist': the distance field's cap (AmclOptions::laser_likelihood_max_dist).
  LocalizationMap(const mapping::MapImage& map, double likelihood_max_dist);
  LocalizationMap(const LocalizationMap&) = delete;
  LocalizationMap& operator=(const LocalizationMap&) = delete;

  const mapping::DistanceField& distance_field() const { return field_; }
  // The same distances as numbers of distinct values (the likelihood field's look-up table).
  const QuantizedDistanceField& quantized_field() const { return quantized_; }
  double resolution() const { return field_.resolution(); }
  int width() const { return field_.width(); }
  int height() const { return field_.height(); }

  mapping::CellState State(const Eigen::Vector2i& cell) const {
    if (!field_.Contains(cell)) return mapping::CellState::kUnknown;
    return states_[static_cast<std::size_t>(cell.y() * width() + cell.x())];
  }
  bool IsFree(const Eigen::Vector2d& world) const {
    return State(field_.CellOf(world)) == mapping::CellState::kFree;
  }
  const std::vector<Eigen::Vector2i>& free_cells() const { return free_cells_; }

  // A pose at the centre of a free cell drawn uniformly, with a uniform heading in [−π, π)
  // (nav2's uniform_pose_generator). Needs a free cell.
  Pose2 RandomFreePose(Rng& rng) const;

  // Distance from 'origin' along heading 'angle' to the first cell that is not free (occupied,
  // unknown or off the map, as nav2's map_calc_range), at most 'max_range'.
  double CalcRange(const Eigen::Vector2d& origin, double angle, double max_range) const;

 private:
  mapping::DistanceField field_;
  QuantizedDistanceField quantized_;
  std::vector<mapping::CellState> states_;
  std::vector<Eigen::Vector2i> free_cells_;
};

}  // namespace semchain::localization
