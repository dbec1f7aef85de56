#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "core/pose2.h"
#include "core/rng.h"
#include "core/status.h"
#include "localization/amcl_options.h"
#include "localization/failure_detector.h"
#include "localization/kld_sampling.h"
#include "localization/laser_model.h"
#include "localization/localization_map.h"
#include "localization/odometry_motion_model.h"
#include "localization/particle_clusters.h"
#include "localization/pose_hypothesis.h"
#include "sensors/laser_scan.h"

// Adaptive Monte Carlo localization as nav2_amcl does it (Thrun et al., Probabilistic Robotics
// Tables 8.2–8.4; Fox 2003): odometry motion model, likelihood-field or beam laser model, KLD
// adaptive resampling with recovery by random particles, updates gated by update_min_d /
// update_min_a, and the estimate as the mean of the heaviest particle cluster. On top, the
// hooks of the improved AMCL of seed 000 §3.2: initialisation from weighted pose hypotheses and a
// pose prior that multiplies each particle's weight by its match probability; and a failure
// detector that tells the caller when to re-run pre-localization.
//
// Typical use:
//   LocalizationMap map(map_image, options.laser_likelihood_max_dist);
//   Amcl amcl(map, options, MakeRng(seed));
//   amcl.InitializeGlobal();                       // or InitializePose / InitializeFromHypotheses
//   for (each scan) if (amcl.ProcessScan(scan, odometry, laser_offset)) use(amcl.Estimate());
namespace semchain::localization {

struct AmclEstimate {
  Pose2 pose;  // mean of the heaviest cluster
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  double cluster_weight = 0.0;  // its share of the total weight, (0, 1]
  int clusters = 0;
  int particles = 0;       // current sample count (KLD-adaptive)
  bool converged = false;  // every particle within convergence_distance of the mean (nav2)
};

struct AmclCounters {
  int updates = 0;                    // sensor updates
  int resamplings = 0;                // resampling steps taken
  std::int64_t random_particles = 0;  // injected by recovery
};

class Amcl {
 public:
  // 'map' must outlive the filter; 'options' must validate.
  Amcl(const LocalizationMap& map, const AmclOptions& options, Rng rng);
  Amcl(const Amcl&) = delete;
  Amcl& operator=(const Amcl&) = delete;

  // Initialisation: max_particles particles, equal weights; the next ProcessScan updates the
  // filter whatever the motion. Each also resets the failure detector.
  // Uniform over the free cells and every heading (global localization, unknown start).
  void InitializeGlobal();
  // A Gaussian around 'mean' (nav2's initial pose with covariance).
  void InitializePose(const Pose2& mean, const Eigen::Matrix3d& covariance);
  // Gaussians around the hypotheses, each getting particles in proportion to its weight
  // (seed 000 §3.2). The list must pass ValidateHypotheses.
  void InitializeFromHypotheses(const std::vector<PoseHypothesis>& hypotheses);

  // The pose prior of seed 000 §3.2: while set, every sensor update multiplies each particle's
  // weight by PosePrior::Probability (floor AmclOptions::pose_prior.floor). The list must pass
  // ValidateHypotheses. The caller decides when to drop it (e.g. once Estimate().converged).
  void SetPosePrior(const std::vector<PoseHypothesis>& hypotheses);
  void ClearPosePrior() { prior_.reset(); }
  bool has_pose_prior() const { return prior_.has_value(); }

  // Feeds one scan with the odometry pose of the robot at its time and the laser's pose in the
  // robot frame. When the odometry moved more than update_min_d (in x or y) or turned more than
  // update_min_a since the last filter update, or on the first scan after an initialisation,
  // runs the motion update, the sensor update and (every resample_interval updates) KLD
  // resampling, and returns true; otherwise returns false and changes nothing.
  bool ProcessScan(const LaserScan& scan, const Pose2& odometry, const Pose2& laser_offset);

  // Moves every particle rigidly (the cloud keeps its shape and weights) so that the estimate
  // lies at 'pose': each particle p becomes pose ⊕ (estimate⁻¹ ⊕ p). A scan matched against the
  // map knows the pose better than the cloud's mean (scan_tracking.h).
  void Recenter(const Pose2& pose);

  // The current estimate (valid after an initialisation).
  AmclEstimate Estimate() const { return estimate_; }
  const std::vector<Particle>& particles() const { return particles_; }

  // True once the filter, having converged, has looked lost for several updates in a row.
  bool FailureDetected() const { return detector_.failed(); }
  const FailureDetector& failure_detector() const { return detector_; }
  // The weighted mean per-beam likelihood of the last sensor update.
  double mean_beam_likelihood() const { return mean_beam_likelihood_; }
  // The recovery averages (AmclOptions::recovery_weighted_mean says of what); 0 after an
  // initialisation and after random particles were injected.
  double w_slow() const { return w_slow_; }
  double w_fast() const { return w_fast_; }
  const AmclCounters& counters() const { return counters_; }
  const AmclOptions& options() const { return options_; }

 private:
  void ResetAfterInitialization();
  void MotionUpdate(const Pose2& odometry);
  void SensorUpdate(const LaserBeams& beams);
  void Resample();
  int SampleLimit(int bins) const;
  void UpdateEstimate();

  const LocalizationMap& map_;
  AmclOptions options_;
  Rng rng_;
  OdometryMotionModel motion_model_;
  std::unique_ptr<LaserModel> laser_model_;
  std::vector<Particle> particles_;
  std::vector<Particle> next_particles_;  // resampling's output buffer, kept to reuse
  PoseBins bins_;                         // resampling's KLD bins, kept to reuse
  std::optional<PosePrior> prior_;
  FailureDetector detector_;
  std::optional<Pose2> last_odometry_;  // at the last filter update; empty after initialisation
  double w_slow_ = 0.0;
  double w_fast_ = 0.0;
  double mean_beam_likelihood_ = 0.0;
  int resample_count_ = 0;
  AmclEstimate estimate_;
  AmclCounters counters_;
};

}  // namespace semchain::localization
