#include "mapping/rbpf_slam.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "core/check.h"
#include "mapping/correlative_scan_matcher.h"
#include "mapping/parallel_for.h"
#include "mapping/ray_casting.h"
#include "mapping/resampling.h"

namespace semchain::mapping {
namespace {

template <typename T>
bool ValidateChild(const T& options, const char* name, std::string* error) {
  if (options.Validate(error)) return true;
  *error = std::string(name) + "." + *error;
  return false;
}

}  // namespace

bool RbpfOptions::Validate(std::string* error) const {
  if (particles < 1 || particles > 10000) {
    *error = "particles must be in [1, 10000]";
    return false;
  }
  if (threads < 0 || !(linear_update_meters >= 0.0 && angular_update_radians >= 0.0)) {
    *error = "threads, linear_update_meters and angular_update_radians must be >= 0";
    return false;
  }
  if (!(resample_threshold >= 0.0 && resample_threshold <= 1.0) || !(weight_gain > 0.0)) {
    *error = "resample_threshold must be in [0, 1] and weight_gain positive";
    return false;
  }
  if (!(match_max_range_meters > 0.0) || match_beam_step < 1) {
    *error = "match_max_range_meters must be positive and match_beam_step >= 1";
    return false;
  }
  return ValidateChild(grid, "grid", error) && ValidateChild(scan, "scan", error) &&
         ValidateChild(field, "likelihood_field", error) &&
         ValidateChild(matcher, "matcher", error) && ValidateChild(motion, "motion", error) &&
         ValidateChild(proposal, "proposal", error) &&
         ValidateChild(annealing, "annealing", error) && ValidateChild(genetic, "genetic", error);
}

RbpfSlam::RbpfSlam(const RbpfOptions& options)
    : options_(options),
      threads_(ResolveThreadCount(options.threads)),
      motion_(options.motion),
      resampling_rng_(MakeRng(options.seed, 0)) {
  std::string error;
  SEMCHAIN_CHECK(options_.Validate(&error));
  for (int i = 0; i < options_.particles; ++i) {
    rngs_.push_back(MakeRng(options_.seed, static_cast<std::uint64_t>(i) + 1));
  }
}

const Particle& RbpfSlam::BestParticle() const {
  SEMCHAIN_CHECK(!particles_.empty());
  return *std::max_element(particles_.begin(), particles_.end(),
                           [](const Particle& a, const Particle& b) {
                             return a.cumulative_log_weight < b.cumulative_log_weight;
                           });
}

bool RbpfSlam::AddScan(const StampedScan& scan, int index) {
  ++statistics_.scans;
  const PreparedScan prepared = PrepareScan(scan.scan, scan.LaserOffset(), options_.scan);
  if (!initialized_) {
    Initialize(prepared, scan.odometry, index);
    return true;
  }
  if (options_.motion.per_reading_noise) {
    motion_.Accumulate(previous_odometry_.Between(scan.odometry), &pending_motion_);
    previous_odometry_ = scan.odometry;
  }
  const Pose2 increment = last_odometry_.Between(scan.odometry);
  const bool moved = std::hypot(increment.x, increment.y) >= options_.linear_update_meters ||
                     std::abs(increment.theta) >= options_.angular_update_radians;
  if (!moved) return false;
  last_odometry_ = scan.odometry;
  ++statistics_.processed;
  // The increment is taken from the two odometry poses themselves (the composed readings may
  // differ from it by rounding); only the noise comes from the readings.
  const MotionStep step = options_.motion.per_reading_noise
                              ? MotionStep{increment, pending_motion_.covariance}
                              : motion_.Step(increment);
  pending_motion_ = MotionStep{};
  Propose(prepared,
          SelectMatchPoints(prepared, options_.match_max_range_meters, options_.match_beam_step),
          step);
  Resample();
  UpdateMaps(prepared, index);
  return true;
}

void RbpfSlam::Follow(const Pose2& correction, const std::shared_ptr<OccupancyGrid>& map,
                      const std::shared_ptr<const TrajectoryNode>& history, int recent) {
  SEMCHAIN_CHECK(initialized_ && map != nullptr && recent >= 1);
  for (Particle& p : particles_) {
    std::vector<const TrajectoryNode*> newest;  // newest first
    for (const TrajectoryNode* node = p.trajectory.get(); static_cast<int>(newest.size()) < recent;
         node = node->parent.get()) {
      SEMCHAIN_CHECK(node != nullptr);
      newest.push_back(node);
    }
    std::shared_ptr<const TrajectoryNode> moved = history;
    for (auto node = newest.rbegin(); node != newest.rend(); ++node) {
      moved = std::make_shared<const TrajectoryNode>(
          TrajectoryNode{correction * (*node)->pose, (*node)->scan_index, moved});
    }
    p.pose = correction * p.pose;
    p.map = map;
    p.trajectory = std::move(moved);
  }
}

void RbpfSlam::Initialize(const PreparedScan& scan, const Pose2& odometry, int index) {
  // The map frame is the odometry frame at the first scan.
  auto map = std::make_shared<OccupancyGrid>(options_.grid);
  InsertScan(scan, odometry, map.get());
  auto node = std::make_shared<const TrajectoryNode>(TrajectoryNode{odometry, index, nullptr});
  particles_.assign(static_cast<std::size_t>(options_.particles),
                    Particle{odometry, 0.0, 0.0, map, node});
  last_odometry_ = odometry;
  previous_odometry_ = odometry;
  initialized_ = true;
  ++statistics_.processed;
}

void RbpfSlam::Propose(const PreparedScan& scan, const MatchPoints& points,
                       const MotionStep& step) {
  const int n = static_cast<int>(particles_.size());
  std::vector<ProposalEvaluation> evaluations(particles_.size());
  std::vector<DominantModel> votes(particles_.size(), DominantModel::kObservation);
  const Eigen::Vector3d motion_sigmas = motion_.Sigmas(step);
  ParallelFor(n, threads_, [&](int i) {
    const Particle& particle = particles_[i];
    const LikelihoodField field(*particle.map, options_.field);
    evaluations[i] = EvaluateProposal(field, points, motion_, particle.pose, step, options_.matcher,
                                      options_.proposal, rngs_[i]);
  });
  const bool none_matched = std::none_of(evaluations.begin(), evaluations.end(),
                                         [](const ProposalEvaluation& e) { return e.matched; });
  // No particle trusted its match: the whole filter lost the scan, and its matches start again
  // from a wider search (ProposalOptions::recovery_window_meters). Without scan matching (the
  // basic RBPF) no match is ever trusted and there is none to start.
  if (none_matched && options_.proposal.use_scan_matching &&
      options_.proposal.recovery_window_meters > 0.0) {
    CorrelativeSearchOptions search;
    search.linear_window_meters = std::min(options_.proposal.recovery_window_meters,
                                           3.0 * motion_sigmas.head<2>().maxCoeff());
    search.angular_window_radians =
        std::min(options_.proposal.recovery_window_radians, 3.0 * motion_sigmas.z());
    ++statistics_.recoveries;
    ParallelFor(n, threads_, [&](int i) {
      const Particle& particle = particles_[i];
      const LikelihoodField field(*particle.map, options_.field);
      const Pose2 prediction = MotionModel::Predict(particle.pose, step.increment);
      const MatchResult found =
          CorrelativeSearch(field, scan, prediction, search, options_.match_max_range_meters);
      evaluations[i] = EvaluateProposal(field, points, motion_, particle.pose, step,
                                        options_.matcher, options_.proposal, rngs_[i], &found.pose);
    });
  }
  if (options_.annealing.enabled) {
    for (int i = 0; i < n; ++i) {
      votes[i] = ClassifyStep(options_.annealing, evaluations[i], options_.proposal, motion_sigmas);
    }
  }
  // Seed 003 eq. 6: exponents 1 - α (observation) and α (motion); plain GMapping: 1 and 1.
  double observation_exponent = 1.0, motion_exponent = 1.0;
  if (options_.annealing.enabled) {
    const double alpha = ChooseAlpha(options_.annealing, votes);
    observation_exponent = 1.0 - alpha;
    motion_exponent = alpha;
    sum_alpha_ += alpha;
  }
  ParallelFor(n, threads_, [&](int i) {
    const GaussianFit fit =
        FitProposal(evaluations[i], observation_exponent, motion_exponent, options_.proposal);
    particles_[i].pose = SampleGaussian(fit, rngs_[i]);
    particles_[i].log_weight += fit.log_normalizer;  // eq. 5 (eq. 7 with annealing)
    particles_[i].cumulative_log_weight += fit.log_normalizer;
  });
  for (const ProposalEvaluation& e : evaluations) statistics_.unmatched += e.matched ? 0 : 1;
}

void RbpfSlam::Resample() {
  std::vector<double> log_weights;
  for (const Particle& p : particles_) log_weights.push_back(p.log_weight);
  std::vector<double> weights = NormalizeLogWeights(log_weights, options_.weight_gain);
  const double neff = EffectiveSampleSize(weights);  // eq. 3
  sum_neff_ += neff;
  statistics_.mean_effective_sample_size = sum_neff_ / statistics_.processed;
  statistics_.mean_alpha = sum_alpha_ / statistics_.processed;
  const double n = static_cast<double>(particles_.size());
  if (neff >= options_.resample_threshold * n) return;
  if (options_.genetic.enabled) {
    const GeneticStatistics stats =
        GeneticResample(options_.genetic, &weights, &particles_, resampling_rng_);
    for (std::size_t i = 0; i < particles_.size(); ++i) {
      particles_[i].log_weight = std::log(weights[i]) / options_.weight_gain;
    }
    ++statistics_.genetic_resamplings;
    statistics_.crossovers += stats.crossovers;
    statistics_.mutations += stats.mutations;
    return;
  }
  const std::vector<int> chosen =
      LowVarianceResample(weights, static_cast<int>(particles_.size()), resampling_rng_);
  std::vector<Particle> next;
  next.reserve(particles_.size());
  for (const int i : chosen) {
    next.push_back(particles_[static_cast<std::size_t>(i)]);
    next.back().log_weight = 0.0;
  }
  particles_ = std::move(next);
  ++statistics_.resamplings;
}

void RbpfSlam::UpdateMaps(const PreparedScan& scan, int index) {
  // Particles holding the same map at the same pose (copies made by resampling) would write the
  // same cells: update once per group and share the result.
  std::map<std::tuple<const OccupancyGrid*, double, double, double>, std::vector<int>> groups;
  std::map<const OccupancyGrid*, int> groups_per_map;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    const Particle& p = particles_[i];
    auto& members = groups[{p.map.get(), p.pose.x, p.pose.y, p.pose.theta}];
    if (members.empty()) ++groups_per_map[p.map.get()];
    members.push_back(static_cast<int>(i));
  }
  // Decided in order: the last group of each map writes it in place when nothing outside the
  // particles holds it, every other group writes a copy (which shares the patches it does not
  // touch). Each parallel write below then touches a grid object no other thread reads.
  std::vector<std::pair<std::shared_ptr<OccupancyGrid>, std::vector<int>>> work;
  for (auto& [key, members] : groups) {
    std::shared_ptr<OccupancyGrid> map = particles_[members.front()].map;
    int& remaining = groups_per_map[map.get()];
    const long holders = std::count_if(particles_.begin(), particles_.end(),
                                       [&map](const Particle& p) { return p.map == map; });
    const bool in_place = --remaining == 0 && map.use_count() == holders + 1;
    if (!in_place) map = std::make_shared<OccupancyGrid>(*map);
    work.emplace_back(std::move(map), std::move(members));
  }
  ParallelFor(static_cast<int>(work.size()), threads_, [&](int g) {
    auto& [map, members] = work[static_cast<std::size_t>(g)];
    InsertScan(scan, particles_[members.front()].pose, map.get());
  });
  for (auto& [map, members] : work) {
    for (const int i : members) {
      Particle& p = particles_[i];
      p.map = map;
      p.trajectory =
          std::make_shared<const TrajectoryNode>(TrajectoryNode{p.pose, index, p.trajectory});
    }
  }
}

}  // namespace semchain::mapping
