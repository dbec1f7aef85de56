#include "localization/amcl.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>

#include "core/angles.h"
#include "core/check.h"
#include "localization/weighted_index_sampler.h"
#include "mapping/resampling.h"

namespace semchain::localization {

Amcl::Amcl(const LocalizationMap& map, const AmclOptions& options, Rng rng)
    : map_(map),
      options_(options),
      rng_(std::move(rng)),
      motion_model_({options.alpha1, options.alpha2, options.alpha3, options.alpha4}),
      laser_model_(MakeLaserModel(map, options)),
      bins_(options.kld_bin_x, options.kld_bin_y, options.kld_bin_theta),
      detector_(options.failure_detector) {
  std::string error;
  SEMCHAIN_CHECK(options_.Validate(&error));
}

void Amcl::ResetAfterInitialization() {
  const double weight = 1.0 / static_cast<double>(particles_.size());
  for (Particle& p : particles_) p.weight = weight;
  last_odometry_.reset();
  w_slow_ = w_fast_ = 0.0;
  resample_count_ = 0;
  detector_.Reset();
  UpdateEstimate();
}

void Amcl::InitializeGlobal() {
  SEMCHAIN_CHECK(!map_.free_cells().empty());
  particles_.assign(static_cast<std::size_t>(options_.max_particles), {});
  for (Particle& p : particles_) p.pose = map_.RandomFreePose(rng_);
  ResetAfterInitialization();
}

void Amcl::InitializePose(const Pose2& mean, const Eigen::Matrix3d& covariance) {
  InitializeFromHypotheses({{mean, covariance, 1.0}});
}

void Amcl::InitializeFromHypotheses(const std::vector<PoseHypothesis>& hypotheses) {
  SEMCHAIN_CHECK(ValidateHypotheses(hypotheses).ok());
  std::vector<double> weights;
  for (const PoseHypothesis& h : hypotheses) weights.push_back(h.weight);
  std::discrete_distribution<std::size_t> pick(weights.begin(), weights.end());
  particles_.assign(static_cast<std::size_t>(options_.max_particles), {});
  for (Particle& p : particles_) p.pose = SamplePose(hypotheses[pick(rng_)], rng_);
  ResetAfterInitialization();
}

void Amcl::SetPosePrior(const std::vector<PoseHypothesis>& hypotheses) {
  prior_.emplace(hypotheses, options_.pose_prior.floor);
}

bool Amcl::ProcessScan(const LaserScan& scan, const Pose2& odometry, const Pose2& laser_offset) {
  SEMCHAIN_CHECK(!particles_.empty());  // initialise first
  if (last_odometry_) {
    const double dx = odometry.x - last_odometry_->x;
    const double dy = odometry.y - last_odometry_->y;
    const double da = AngleDifference(odometry.theta, last_odometry_->theta);
    if (std::abs(dx) <= options_.update_min_d && std::abs(dy) <= options_.update_min_d &&
        std::abs(da) <= options_.update_min_a) {
      return false;
    }
    MotionUpdate(odometry);
  }
  last_odometry_ = odometry;
  SensorUpdate(SelectBeams(scan, laser_offset, options_));
  if (++resample_count_ % options_.resample_interval == 0) Resample();
  UpdateEstimate();
  if (estimate_.cluster_weight >= 0.9 &&
      std::sqrt(std::max(estimate_.covariance(0, 0), estimate_.covariance(1, 1))) <=
          options_.convergence_distance) {
    detector_.Arm();
  }
  return true;
}

void Amcl::Recenter(const Pose2& pose) {
  SEMCHAIN_CHECK(!particles_.empty());  // initialise first
  const Pose2 correction = pose * estimate_.pose.Inverse();
  for (Particle& p : particles_) p.pose = correction * p.pose;
  UpdateEstimate();
}

void Amcl::MotionUpdate(const Pose2& odometry) {
  const OdometryMotion u = OdometryMotion::Between(*last_odometry_, odometry);
  const OdometryMotionModel::Sigmas sigmas = motion_model_.SigmasOf(u);
  for (Particle& p : particles_) p.pose = OdometryMotionModel::Sample(p.pose, u, sigmas, rng_);
}

void Amcl::SensorUpdate(const LaserBeams& beams) {
  // Weights are normalised before the update, so Σ wᵢ pᵢ is the weighted mean likelihood.
  double total = 0.0, beam_sum = 0.0;
  const auto apply = [&](Particle& p, double likelihood, double mean_beam) {
    beam_sum += p.weight * mean_beam;
    p.weight *= likelihood;
    total += p.weight;
  };
  // Four particles at a time where the model is faster so; the sums in particle order as before.
  std::size_t i = 0;
  for (; i + 4 <= particles_.size(); i += 4) {
    std::array<double, 4> likelihoods, mean_beams;
    laser_model_->Weight4(beams,
                          {&particles_[i].pose, &particles_[i + 1].pose, &particles_[i + 2].pose,
                           &particles_[i + 3].pose},
                          &likelihoods, &mean_beams);
    for (std::size_t k = 0; k < 4; ++k) apply(particles_[i + k], likelihoods[k], mean_beams[k]);
  }
  for (; i < particles_.size(); ++i) {
    double mean_beam = 0.0;
    const double likelihood = laser_model_->Weight(beams, particles_[i].pose, &mean_beam);
    apply(particles_[i], likelihood, mean_beam);
  }
  mean_beam_likelihood_ = beam_sum;
  ++counters_.updates;
  // Probabilistic Robotics Table 8.3 as nav2 pf_update_sensor keeps it (w_avg = total / N), or
  // the weighted mean likelihood itself (recovery_weighted_mean). With both alphas 0 (nav2's
  // default) the averages keep their first value and never call for random particles.
  if (total > 0.0) {
    const double average =
        options_.recovery_weighted_mean ? total : total / static_cast<double>(particles_.size());
    w_slow_ =
        w_slow_ == 0.0 ? average : w_slow_ + options_.recovery_alpha_slow * (average - w_slow_);
    w_fast_ =
        w_fast_ == 0.0 ? average : w_fast_ + options_.recovery_alpha_fast * (average - w_fast_);
  }
  detector_.Update(total - 1.0, mean_beam_likelihood_);
  if (prior_) {
    for (Particle& p : particles_) p.weight *= prior_->Probability(p.pose);
  }
  double sum = 0.0;
  for (const Particle& p : particles_) sum += p.weight;
  const double n = static_cast<double>(particles_.size());
  for (Particle& p : particles_) p.weight = sum > 0.0 ? p.weight / sum : 1.0 / n;
}

int Amcl::SampleLimit(int bins) const {
  // nav2 pf_resample_limit: one bin (or none) keeps max_particles.
  if (bins <= 1) return options_.max_particles;
  const double n = std::ceil(KldSampleBound(bins, options_.pf_err, options_.pf_z));
  return static_cast<int>(std::clamp(n, static_cast<double>(options_.min_particles),
                                     static_cast<double>(options_.max_particles)));
}

void Amcl::Resample() {
  std::vector<double> weights;
  weights.reserve(particles_.size());
  for (const Particle& p : particles_) weights.push_back(p.weight);
  if (options_.selective_resampling &&
      mapping::EffectiveSampleSize(weights) >= 0.5 * static_cast<double>(particles_.size())) {
    return;
  }
  ++counters_.resamplings;
  const double w_diff = w_slow_ > 0.0 ? std::max(0.0, 1.0 - w_fast_ / w_slow_) : 0.0;
  // KLD sampling (Fox 2003, Table 1): draw until the sample count exceeds the bound for the
  // bins occupied so far (nav2 pf_update_resample). Each draw inverts the cumulative weights in
  // expected constant time and the bound is recomputed only when a bin is added, so a
  // resampling is linear in the particle count (nav2's walks the cumulative sum per draw).
  const WeightedIndexSampler sampler(weights);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  bins_.Clear(particles_.size());
  std::vector<Particle>& next = next_particles_;
  next.clear();
  next.reserve(static_cast<std::size_t>(options_.max_particles));
  // A random prefix of a shuffled comb is a draw without replacement from it, so whatever
  // count KLD stops at keeps the comb's low variance.
  std::vector<std::size_t> comb;
  if (options_.systematic_resampling) {
    comb = SystematicDraws(sampler, static_cast<std::size_t>(options_.max_particles),
                           std::min(unit(rng_), std::nextafter(1.0, 0.0)));
    std::shuffle(comb.begin(), comb.end(), rng_);
  }
  int limit = SampleLimit(0);
  while (static_cast<int>(next.size()) < options_.max_particles) {
    Pose2 pose;
    if (w_diff > 0.0 && unit(rng_) < w_diff) {
      pose = map_.RandomFreePose(rng_);
      ++counters_.random_particles;
    } else {
      const std::size_t index = options_.systematic_resampling
                                    ? comb[next.size()]
                                    : sampler.IndexOf(unit(rng_) * sampler.total());
      pose = particles_[index].pose;
    }
    next.push_back({pose, 1.0});
    if (bins_.Insert(pose)) limit = SampleLimit(bins_.count());
    if (static_cast<int>(next.size()) > limit) break;
  }
  if (w_diff > 0.0) w_slow_ = w_fast_ = 0.0;  // as nav2: restart the averages after injecting
  const double weight = 1.0 / static_cast<double>(next.size());
  for (Particle& p : next) p.weight = weight;
  particles_.swap(next);  // the old set's storage is reused by the next resampling
}

void Amcl::UpdateEstimate() {
  const std::vector<PoseCluster> clusters = ClusterParticles(
      particles_, {options_.kld_bin_x, options_.kld_bin_y, options_.kld_bin_theta});
  estimate_ = AmclEstimate();
  estimate_.particles = static_cast<int>(particles_.size());
  estimate_.clusters = static_cast<int>(clusters.size());
  if (!clusters.empty()) {
    estimate_.pose = clusters.front().mean;
    estimate_.covariance = clusters.front().covariance;
    estimate_.cluster_weight = clusters.front().weight;
  }
  // nav2 pf_update_converged: unweighted mean, every particle within the distance in x and y.
  double mx = 0.0, my = 0.0;
  for (const Particle& p : particles_) {
    mx += p.pose.x;
    my += p.pose.y;
  }
  mx /= static_cast<double>(particles_.size());
  my /= static_cast<double>(particles_.size());
  estimate_.converged = std::all_of(particles_.begin(), particles_.end(), [&](const Particle& p) {
    return std::abs(p.pose.x - mx) <= options_.convergence_distance &&
           std::abs(p.pose.y - my) <= options_.convergence_distance;
  });
}

}  // namespace semchain::localization
