#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "core/pose2.h"
#include "localization/amcl_options.h"
#include "localization/likelihood_field_avx2.h"
#include "localization/localization_map.h"
#include "sensors/laser_scan.h"

// The laser measurement models of AMCL (Probabilistic Robotics §6.3 and §6.4, as nav2 amcl
// evaluates them). Both return nav2's particle weight factor 1 + Σ pz³ over the used beams
// rather than the product Π pz: nav2 (and ROS amcl before it) combine beams this way because the
// product of 60 correlated beams is far too peaked; keeping it keeps nav2's behaviour.
namespace semchain::localization {

// The beams of one scan that the models use: at most max_beams, evenly spaced as nav2 picks
// them (every ⌊(n − 1) / (max_beams − 1)⌋-th beam from the first) or over the returns only
// (AmclOptions::beam_selection).
struct LaserBeams {
  Pose2 laser_offset;  // laser pose in the robot frame
  double range_max = 0.0;
  std::vector<double> ranges;    // metres; >= range_max means no return
  std::vector<double> bearings;  // radians, laser frame
  // (cos, sin) of each bearing, so that a particle costs one rotation per beam, not two trig
  // calls.
  std::vector<Eigen::Vector2d> directions;
  // The beams with a return (range < range_max), in order, as separate arrays of ranges and
  // direction components: what the likelihood field reads four at a time. 'hits' of them; the
  // arrays are padded with zeros to a multiple of four. Filled by SelectBeams only
  // ('hit_arrays' says so; without them the model reads 'ranges' and 'directions').
  bool hit_arrays = false;
  int hits = 0;
  std::vector<double> hit_ranges, hit_x, hit_y;
};

// Selects the beams of 'scan' for 'options' (max_beams, beam_selection, laser_min_range,
// laser_max_range); readings at or below the minimum range, non-finite or non-positive count as
// max range.
LaserBeams SelectBeams(const LaserScan& scan, const Pose2& laser_offset,
                       const AmclOptions& options);

class LaserModel {
 public:
  virtual ~LaserModel() = default;
  // The weight factor of a robot at 'pose' for 'beams'; '*mean_beam' receives the mean pz of
  // the beams used (0 when none was).
  virtual double Weight(const LaserBeams& beams, const Pose2& pose, double* mean_beam) const = 0;
  // The same for four poses: weights[i] and mean_beams[i] as Weight(beams, *poses[i], ...) gives
  // them. Models override it where four at a time is faster.
  virtual void Weight4(const LaserBeams& beams, const std::array<const Pose2*, 4>& poses,
                       std::array<double, 4>* weights, std::array<double, 4>* mean_beams) const {
    for (std::size_t i = 0; i < 4; ++i) {
      (*weights)[i] = Weight(beams, *poses[i], &(*mean_beams)[i]);
    }
  }
};

// nav2 likelihood_field: pz = z_hit exp(−d² / 2σ_hit²) + z_rand / range_max, d the distance from
// the beam endpoint to the nearest occupied cell (laser_likelihood_max_dist off the map);
// max-range readings are skipped.
class LikelihoodFieldModel : public LaserModel {
 public:
  // 'map' must outlive the model.
  LikelihoodFieldModel(const LocalizationMap& map, const AmclOptions& options);
  double Weight(const LaserBeams& beams, const Pose2& pose, double* mean_beam) const override;
  // With AVX2, the four running sums Σ pz³ interleaved: each is a chain of dependent additions
  // (kept in beam order for the same result), and four chains keep the adder busy.
  void Weight4(const LaserBeams& beams, const std::array<const Pose2*, 4>& poses,
               std::array<double, 4>* weights, std::array<double, 4>* mean_beams) const override;
  // pz of one beam whose endpoint is 'distance' from the nearest obstacle.
  double BeamLikelihood(double distance, double range_max) const;

 private:
  // Weight with the AVX2 kernel over the beams' hit arrays; 'rand_term' = z_rand / range_max.
  double WeightAvx2(const LaserBeams& beams, const LaserFrame& frame, double rand_term,
                    double* mean_beam) const;
  // Weight on the distance field itself (maps whose distances the quantized field cannot name).
  double WeightDirect(const LaserBeams& beams, const Pose2& pose, double* mean_beam) const;

  const LocalizationMap& map_;
  double z_hit_, z_rand_, factor_;
  // z_hit exp(−d² / 2σ²) for each distinct distance of map_.quantized_field() (Prob. Rob.
  // §6.4's precomputed likelihood field, per distance instead of per cell).
  std::vector<double> hit_terms_;
};

// nav2 beam: the expected range z* is ray cast on the map; pz = z_hit exp(−(z − z*)² / 2σ_hit²)
// (unnormalised, as in nav2) + z_short λ e^{−λz} when z < z*, + z_max for a reading of exactly
// range_max, + z_rand / range_max for one below it (a reading beyond range_max gets neither).
class BeamModel : public LaserModel {
 public:
  BeamModel(const LocalizationMap& map, const AmclOptions& options);
  double Weight(const LaserBeams& beams, const Pose2& pose, double* mean_beam) const override;
  // pz of a reading 'range' where the map predicts 'expected'.
  double BeamLikelihood(double range, double expected, double range_max) const;

 private:
  const LocalizationMap& map_;
  AmclOptions options_;
};

std::unique_ptr<LaserModel> MakeLaserModel(const LocalizationMap& map, const AmclOptions& options);

}  // namespace semchain::localization
