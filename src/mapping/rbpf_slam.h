#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/rng.h"
#include "mapping/annealing.h"
#include "mapping/genetic_resampling.h"
#include "mapping/hill_climbing_matcher.h"
#include "mapping/likelihood_field.h"
#include "mapping/motion_model.h"
#include "mapping/occupancy_grid.h"
#include "mapping/particle.h"
#include "mapping/prepared_scan.h"
#include "mapping/proposal.h"
#include "sensors/laser_scan.h"

// Rao-Blackwellized particle filter SLAM (seed 003; GMapping as in seed 004 §1.2): each particle
// carries a pose, a weight, its trajectory and its map. Per processed scan: improved proposal
// (eq. 4–5, optionally annealed, eq. 6), weights by the proposal's normaliser, selective
// resampling when N_eff < N_th (eq. 3) — low-variance, or adaptive genetic (eq. 8–10) — and the
// map update. Maps are shared copy-on-write; the particle loop runs on several threads and the
// result depends only on the seed (each particle slot has its own random stream).
namespace semchain::mapping {

struct RbpfOptions {
  int particles = 30;
  std::uint64_t seed = 1;
  int threads = 0;  // 0 = one per core
  // A scan is processed once the odometry moved this far or turned this much since the last
  // processed scan (GMapping linearUpdate / angularUpdate); 0 and 0 process every scan.
  double linear_update_meters = 1.0;
  double angular_update_radians = 0.5;
  // Selective resampling: resample when N_eff < resample_threshold × N (eq. 3; GMapping 0.5).
  double resample_threshold = 0.5;
  // Normalised weights are ∝ exp(weight_gain × log w): a temperature on the accumulated
  // log-weights, since the beams of a scan are far from independent (GMapping uses
  // 1 / (3 N) on its own likelihood scale).
  double weight_gain = 0.05;
  // Scan matching uses returns up to this range, every 'match_beam_step'-th one.
  double match_max_range_meters = 30.0;
  int match_beam_step = 2;

  OccupancyGridOptions grid;
  ScanPreparationOptions scan;
  LikelihoodFieldOptions field;
  HillClimbingOptions matcher;
  MotionModelOptions motion;
  ProposalOptions proposal;
  AnnealingOptions annealing;
  GeneticResamplingOptions genetic;

  bool Validate(std::string* error) const;
};

struct RbpfStatistics {
  int scans = 0;
  int processed = 0;
  int resamplings = 0;          // low-variance resamplings
  int genetic_resamplings = 0;  // genetic operations instead of resampling
  int crossovers = 0;
  int mutations = 0;
  int unmatched = 0;   // particle updates whose scan match was not trusted
  int recoveries = 0;  // steps where no particle matched and a wider search was run
  double mean_effective_sample_size = 0.0;
  double mean_alpha = 0.0;  // over processed scans, with annealing
};

class RbpfSlam {
 public:
  explicit RbpfSlam(const RbpfOptions& options);
  RbpfSlam(const RbpfSlam&) = delete;
  RbpfSlam& operator=(const RbpfSlam&) = delete;

  // Feeds the next scan of the log ('index' counts scans from 0); returns true when it was
  // processed (the first scan, and then whenever the robot moved enough).
  bool AddScan(const StampedScan& scan, int index);

  const std::vector<Particle>& particles() const { return particles_; }
  // The particle with the highest accumulated weight.
  const Particle& BestParticle() const;
  const RbpfStatistics& statistics() const { return statistics_; }
  const RbpfOptions& options() const { return options_; }

  // Moves the filter onto a corrected trajectory (the pose graph's, after a loop closure):
  // every particle's pose and its newest 'recent' trajectory nodes (≥ 1) are premultiplied by
  // 'correction' (a change of map frame), and every particle takes 'map' and, as its trajectory
  // before those nodes, 'history' (newest first; may be null). Weights and random streams are
  // kept.
  void Follow(const Pose2& correction, const std::shared_ptr<OccupancyGrid>& map,
              const std::shared_ptr<const TrajectoryNode>& history, int recent);

  // Drops the particles and their maps (a campus map takes hundreds of MB): afterwards only
  // statistics() and options() may be asked.
  void DropParticles() { particles_ = {}; }

 private:
  void Initialize(const PreparedScan& scan, const Pose2& odometry, int index);
  void Propose(const PreparedScan& scan, const MatchPoints& points, const MotionStep& step);
  void Resample();
  void UpdateMaps(const PreparedScan& scan, int index);

  RbpfOptions options_;
  int threads_;
  MotionModel motion_;
  std::vector<Particle> particles_;
  std::vector<Rng> rngs_;  // one per particle slot
  Rng resampling_rng_;
  bool initialized_ = false;
  Pose2 last_odometry_;  // at the last processed scan
  // With per_reading_noise: the odometry at the last scan and the readings since the last
  // processed scan.
  Pose2 previous_odometry_;
  MotionStep pending_motion_;
  RbpfStatistics statistics_;
  double sum_neff_ = 0.0;
  double sum_alpha_ = 0.0;
};

}  // namespace semchain::mapping
