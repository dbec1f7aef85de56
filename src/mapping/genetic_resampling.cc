#include "mapping/genetic_resampling.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "core/angles.h"
#include "core/check.h"

namespace semchain::mapping {

bool GeneticResamplingOptions::Validate(std::string* error) const {
  if (!(high_weight_factor > 1.0 && low_weight_factor > 0.0 && low_weight_factor < 1.0)) {
    *error = "need high_weight_factor > 1 and 0 < low_weight_factor < 1";
    return false;
  }
  for (const double rate : {crossover_rate_1, crossover_rate_2, mutation_rate_1, mutation_rate_2}) {
    if (!(rate >= 0.0 && rate <= 1.0)) {
      *error = "crossover and mutation rates must be in [0, 1]";
      return false;
    }
  }
  if (!(beta >= 0.0 && crossover_max_blend >= 0.0 && crossover_max_blend <= 1.0)) {
    *error = "need beta >= 0 and crossover_max_blend in [0, 1]";
    return false;
  }
  if (!(crossover_max_distance_meters >= 0.0 && crossover_max_angle_radians >= 0.0 &&
        mutation_sigma_meters >= 0.0 && mutation_sigma_radians >= 0.0)) {
    *error = "crossover distances and mutation sigmas must be >= 0";
    return false;
  }
  return true;
}

double AdaptiveRate(double f, double f_average, double f_max, double rate_1, double rate_2,
                    double beta) {
  if (f < f_average) return rate_1;
  if (f_max <= f_average) return 0.5 * (rate_1 + rate_2);  // every particle equally fit
  const double x = 2.0 * (f - f_average) / (f_max - f_average);
  return rate_2 + (rate_1 - rate_2) / (1.0 + std::exp(beta * x));
}

namespace {

Pose2 Crossover(const GeneticResamplingOptions& options, const Pose2& high, const Pose2& low,
                Rng& rng) {
  const Pose2 difference = high.Between(low);
  if (std::hypot(difference.x, difference.y) > options.crossover_max_distance_meters ||
      std::abs(difference.theta) > options.crossover_max_angle_radians) {
    return high;
  }
  const double xi = std::uniform_real_distribution<double>(0.0, options.crossover_max_blend)(rng);
  return Interpolate(high, low, xi);
}

Pose2 Mutate(const GeneticResamplingOptions& options, const Pose2& pose, Rng& rng) {
  std::normal_distribution<double> normal;
  // θ, y, x, one statement each: a constructor's arguments are evaluated in an unspecified order
  // (GCC last to first, as the published ablation was run; clang first to last).
  const double theta = pose.theta + options.mutation_sigma_radians * normal(rng);
  const double y = pose.y + options.mutation_sigma_meters * normal(rng);
  const double x = pose.x + options.mutation_sigma_meters * normal(rng);
  return Pose2(x, y, theta);
}

}  // namespace

namespace {

// Crossover (eq. 9): each low particle, with probability P_c, becomes the child of a random
// high particle. Fills parent_of[child] and children[parent].
void Crossovers(const GeneticResamplingOptions& options, const std::vector<double>& weights,
                const std::vector<int>& high, std::vector<int> low,
                std::vector<Particle>* particles, std::vector<int>* parent_of,
                std::vector<int>* children, Rng& rng, GeneticStatistics* stats) {
  if (high.empty()) return;
  const double f_average = 1.0 / static_cast<double>(weights.size());
  const double f_max = *std::max_element(weights.begin(), weights.end());
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::shuffle(low.begin(), low.end(), rng);
  for (const int l : low) {
    const int h = high[std::uniform_int_distribution<std::size_t>(0, high.size() - 1)(rng)];
    const double f_prime = std::max(weights[h], weights[l]);  // eq. 9: the fitter parent
    const double p_c = AdaptiveRate(f_prime, f_average, f_max, options.crossover_rate_1,
                                    options.crossover_rate_2, options.beta);
    if (uniform(rng) >= p_c) continue;
    Particle& child = (*particles)[l];
    const Particle& parent = (*particles)[h];
    child.pose = Crossover(options, parent.pose, child.pose, rng);
    child.map = parent.map;  // a child's map is its high-weight parent's
    child.trajectory = parent.trajectory;
    child.cumulative_log_weight = parent.cumulative_log_weight;
    (*parent_of)[l] = h;
    ++(*children)[h];
    ++stats->crossovers;
  }
}

// Each high parent shares its weight with its children (mass is preserved); then mutation
// (eq. 10) of each child with probability P_m. Returns the new normalised weights.
std::vector<double> ShareAndMutate(const GeneticResamplingOptions& options,
                                   const std::vector<double>& weights,
                                   const std::vector<int>& parent_of,
                                   const std::vector<int>& children,
                                   std::vector<Particle>* particles, Rng& rng,
                                   GeneticStatistics* stats) {
  const std::size_t n = weights.size();
  std::vector<double> shared = weights;
  for (std::size_t i = 0; i < n; ++i) {
    if (parent_of[i] >= 0) {
      shared[i] = weights[parent_of[i]] / (children[parent_of[i]] + 1);
    } else if (children[i] > 0) {
      shared[i] = weights[i] / (children[i] + 1);
    }
  }
  double sum = 0.0;
  for (const double w : shared) sum += w;
  for (double& w : shared) w /= sum;
  const double f_max = *std::max_element(shared.begin(), shared.end());
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (parent_of[i] < 0) continue;
    const double p_m = AdaptiveRate(shared[i], 1.0 / static_cast<double>(n), f_max,
                                    options.mutation_rate_1, options.mutation_rate_2,
                                    options.beta);  // eq. 10
    if (uniform(rng) < p_m) {
      (*particles)[i].pose = Mutate(options, (*particles)[i].pose, rng);
      ++stats->mutations;
    }
  }
  return shared;
}

}  // namespace

GeneticStatistics GeneticResample(const GeneticResamplingOptions& options,
                                  std::vector<double>* normalized_weights,
                                  std::vector<Particle>* particles, Rng& rng) {
  const std::vector<double>& weights = *normalized_weights;
  const int n = static_cast<int>(particles->size());
  SEMCHAIN_CHECK(static_cast<int>(weights.size()) == n && n > 0);
  // Eq. 8: high above W_H0 = 2/N, low below W_L0 = 1/(2N), medium in between.
  std::vector<int> high, low;
  for (int i = 0; i < n; ++i) {
    if (weights[i] > options.high_weight_factor / n) {
      high.push_back(i);
    } else if (weights[i] < options.low_weight_factor / n) {
      low.push_back(i);
    }
  }
  GeneticStatistics stats;
  stats.high = static_cast<int>(high.size());
  stats.low = static_cast<int>(low.size());
  stats.medium = n - stats.high - stats.low;
  std::vector<int> parent_of(static_cast<std::size_t>(n), -1);
  std::vector<int> children(static_cast<std::size_t>(n), 0);
  Crossovers(options, weights, high, low, particles, &parent_of, &children, rng, &stats);
  *normalized_weights =
      ShareAndMutate(options, weights, parent_of, children, particles, rng, &stats);
  return stats;
}

}  // namespace semchain::mapping
