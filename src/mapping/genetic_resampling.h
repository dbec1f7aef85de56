#pragma once

#include <string>
#include <vector>

#include "core/rng.h"
#include "mapping/particle.h"

// Adaptive genetic resampling (seed 003 §2.2, eq. 8–10). Instead of drawing a new particle set,
// particles are classified by normalised weight (fitness F = w̃): high (w̃ > 2/N), low
// (w̃ < 1/(2N)) and medium (eq. 8). Each low particle is crossed with a random high one with the
// adaptive rate P_c (eq. 9); the child replaces the low particle, takes the high parent's map and
// trajectory (its map must agree with the pose history it was built from) and a pose between
// the two parents', and is mutated with the adaptive rate P_m (eq. 10). High and medium
// particles are kept. A high parent's weight is shared equally with its children, so the total
// weight, and hence the estimate, is preserved as in ordinary resampling.
namespace semchain::mapping {

struct GeneticResamplingOptions {
  // false: plain low-variance resampling whenever N_eff < N_th (GMapping).
  bool enabled = false;
  double high_weight_factor = 2.0;  // W_H0 = factor / N (eq. 8)
  double low_weight_factor = 0.5;   // W_L0 = factor / N (eq. 8)
  double crossover_rate_1 = 0.7;    // P_c1 (seed 003 §3.1)
  double crossover_rate_2 = 0.5;    // P_c2
  double mutation_rate_1 = 0.1;     // P_m1
  double mutation_rate_2 = 0.01;    // P_m2
  // β of eq. 9–10; the paper gives no value: 9.903438 is the usual choice of the sigmoid
  // adaptive GA it follows (the rate falls from midway to P_x2 over [F_avg, F_max]).
  double beta = 9.903438;
  // Crossover: child pose = high ⊕ ξ (low - high), ξ ~ U(0, max_blend).
  double crossover_max_blend = 0.5;
  // Parents farther apart than this lie in different modes (and maps): the child then copies
  // the high parent's pose instead of blending.
  double crossover_max_distance_meters = 0.2;
  double crossover_max_angle_radians = 0.1;
  // Mutation: Gaussian jitter of the pose.
  double mutation_sigma_meters = 0.02;
  double mutation_sigma_radians = 0.01;

  bool Validate(std::string* error) const;
};

// Eq. 9 / eq. 10: the adaptive rate for fitness 'f' (F' for crossover, F for mutation) given
// the population's mean and maximum fitness; 'rate_1' below the mean, falling towards 'rate_2'
// as f approaches the maximum.
double AdaptiveRate(double f, double f_average, double f_max, double rate_1, double rate_2,
                    double beta);

struct GeneticStatistics {
  int high = 0, medium = 0, low = 0;
  int crossovers = 0;
  int mutations = 0;
};

// Applies crossover and mutation to 'particles' whose normalised weights are
// '*normalized_weights'; on return those hold the particles' new normalised weights.
GeneticStatistics GeneticResample(const GeneticResamplingOptions& options,
                                  std::vector<double>* normalized_weights,
                                  std::vector<Particle>* particles, Rng& rng);

}  // namespace semchain::mapping
