#pragma once

#include <string>

#include "core/angles.h"

// Every AMCL parameter in one place, named and defaulted as nav2_amcl names and defaults them
// (nav2 a3a9704, nav2_params.yaml and amcl_node.cpp), so that a nav2 user's configuration
// carries over. Units: metres, radians, seconds.
namespace semchain::localization {

enum class LaserModelType { kLikelihoodField, kBeam };

// Which beams of a scan the laser model reads (max_beams of them).
//   kEvenly   nav2: every ⌊(n − 1) / (max_beams − 1)⌋-th beam from the first, no-return readings
//             included (the likelihood field skips them, the beam model scores them z_max)
//   kReturns  max_beams spaced evenly over the beams that have a return: a lidar whose readings
//             are mostly empty (a Neato's: 70 % zeros) keeps max_beams beams on obstacles
//             instead of a third of them
enum class BeamSelection { kEvenly, kReturns };

// The weight a particle gets from a hypothesis list (seed 000 §3.2): see PosePrior.
struct PosePriorOptions {
  // A particle far from every hypothesis keeps this fraction of its weight: it loses against
  // near particles but does not vanish, so a wrong prior can still be overruled by the laser.
  double floor = 0.05;

  bool Validate(std::string* error) const;
};

// Online failure detection (DESIGN §3.8 "going beyond"): the filter is flagged as lost when,
// for 'consecutive_updates' sensor updates in a row after it has localized (the heaviest
// cluster holds 90 % of the weight with a position σ within convergence_distance), the
// short-term average likelihood falls below 'min_fast_slow_ratio' of the long-term one (w_fast /
// w_slow of Probabilistic Robotics Table 8.3, with its own averages so that it works with
// recovery off) or the mean per-beam likelihood pz falls below 'min_mean_beam_likelihood'.
struct FailureDetectorOptions {
  double alpha_slow = 0.001;  // the ROS wiki's suggested recovery_alpha_slow
  double alpha_fast = 0.1;    // ... and recovery_alpha_fast
  // The averages are of Σ pz³: a localized filter has beams near pz ≈ 0.5 (pz³ ≈ 0.1), a lost
  // one near 0.1 (0.001), so a collapse divides them by far more than 3.
  double min_fast_slow_ratio = 0.3;
  // With nav2's likelihood field a beam on a wall scores z_hit + z_rand / range ≈ 0.5; 0.1 is
  // a mean beam about 2 sigma_hit (0.4 m) off the nearest wall.
  double min_mean_beam_likelihood = 0.1;
  int consecutive_updates = 5;

  bool Validate(std::string* error) const;
};

struct AmclOptions {
  // Odometry motion model, differential drive (Probabilistic Robotics Table 5.6; nav2
  // DifferentialMotionModel). Variances: rot ← alpha1 rot² + alpha2 trans²,
  // trans ← alpha3 trans² + alpha4 (rot1² + rot2²).
  double alpha1 = 0.2;  // rotation noise from rotation
  double alpha2 = 0.2;  // rotation noise from translation
  double alpha3 = 0.2;  // translation noise from translation
  double alpha4 = 0.2;  // translation noise from rotation

  // Laser model (nav2 laser_model_type "likelihood_field" or "beam").
  LaserModelType laser_model_type = LaserModelType::kLikelihoodField;
  int max_beams = 60;  // beams used per scan (beam_selection)
  BeamSelection beam_selection = BeamSelection::kEvenly;
  double laser_max_range = 100.0;          // <= 0: the scan's own max range
  double laser_min_range = -1.0;           // <= 0: none; shorter readings count as max range
  double laser_likelihood_max_dist = 2.0;  // distance field cap (likelihood field)
  double z_hit = 0.5;
  double z_short = 0.05;  // beam model only
  double z_max = 0.05;    // beam model only
  double z_rand = 0.5;
  double sigma_hit = 0.2;
  double lambda_short = 0.1;  // beam model only

  // Particles and KLD sampling (Fox 2003). nav2 uses pf_z as the standard normal quantile
  // itself (0.99, i.e. about 84 % confidence, not the 2.33 of a 99 % quantile); we keep that so
  // that particle counts match nav2's.
  int min_particles = 500;
  int max_particles = 2000;
  double pf_err = 0.05;
  double pf_z = 0.99;
  // KLD histogram bins (nav2 pf_kdtree: 0.5 m, 0.5 m, 10°); clusters use the same bins.
  double kld_bin_x = 0.5;
  double kld_bin_y = 0.5;
  double kld_bin_theta = DegToRad(10.0);

  // Recovery (Probabilistic Robotics Table 8.3): random particles are injected with probability
  // max(0, 1 − w_fast / w_slow). nav2's default 0.0 turns it off; 0.001 / 0.1 are usual values.
  double recovery_alpha_slow = 0.0;
  double recovery_alpha_fast = 0.0;
  // What w_slow / w_fast average. false (nav2 pf_update_sensor): the mean particle weight after
  // the update, Σ wᵢ pᵢ / N with Σ wᵢ = 1, which jumps whenever KLD changes N (a growing sample
  // set looks like a likelihood drop and injects particles). true: the weighted mean likelihood
  // Σ wᵢ pᵢ, which does not depend on N.
  bool recovery_weighted_mean = false;

  int resample_interval = 1;  // resample every n-th sensor update
  // ROS amcl's selective_resampling (off by default, as there): resample only when
  // N_eff < N / 2 (Doucet; seed 003 eq. 3).
  bool selective_resampling = false;
  // How resampling picks the survivors. false (nav2 pf_update_resample): independent draws
  // from the weights (multinomial). true: a systematic comb of max_particles evenly spaced
  // draws with one random offset, taken in random order until KLD's bound is reached, so a
  // particle of weight w survives about w·N times instead of Binomial(N, w) times.
  bool systematic_resampling = false;

  // Filter updates happen when odometry moved this far (per axis, as nav2) or turned this much.
  double update_min_d = 0.25;
  double update_min_a = 0.2;

  // nav2 pf dist_threshold: converged when every particle is within this of the mean in x and y.
  double convergence_distance = 0.5;

  PosePriorOptions pose_prior;
  FailureDetectorOptions failure_detector;

  bool Validate(std::string* error) const;
};

}  // namespace semchain::localization
