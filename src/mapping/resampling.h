#pragma once

#include <vector>

#include "core/rng.h"

// Resampling shared by the RBPF and AMCL.
namespace semchain::mapping {

// Weights proportional to exp(gain × log_weight), normalised to sum to 1 (computed relative to
// the largest log-weight, so that very negative log-likelihoods do not underflow).
std::vector<double> NormalizeLogWeights(const std::vector<double>& log_weights, double gain = 1.0);

// N_eff = 1 / Σ w̃ᵢ² for normalised weights w̃ (seed 003 eq. 3).
double EffectiveSampleSize(const std::vector<double>& normalized_weights);

// Low-variance (systematic) resampling (Probabilistic Robotics Table 4.4): 'count' indices
// drawn with probability proportional to 'normalized_weights' using one random offset, in
// ascending order.
std::vector<int> LowVarianceResample(const std::vector<double>& normalized_weights, int count,
                                     Rng& rng);

}  // namespace semchain::mapping
