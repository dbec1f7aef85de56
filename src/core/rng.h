#pragma once

#include <cstdint>
#include <random>

namespace semchain {

// Every stochastic component takes one of these, seeded explicitly by its caller.
using Rng = std::mt19937_64;

// An independent, reproducible stream for component 'stream' of an experiment seeded 'seed'
// (so adding draws to one component never changes another's numbers).
inline Rng MakeRng(std::uint64_t seed, std::uint64_t stream = 0) {
  std::seed_seq sequence{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                         static_cast<std::uint32_t>(stream),
                         static_cast<std::uint32_t>(stream >> 32)};
  return Rng(sequence);
}

}  // namespace semchain
