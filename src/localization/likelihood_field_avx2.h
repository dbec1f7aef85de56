#pragma once

#include "localization/quantized_distance_field.h"

// The likelihood field's inner loop four beams at a time with AVX2, for CPUs that have it
// (checked at run time; the build targets baseline x86-64). Each lane does the scalar code's
// IEEE operations in their order, without fused multiply-adds, so the pz are the same to the
// last bit; lanes whose endpoint lies within a hair of a cell border take the scalar exact path.
namespace semchain::localization {

// A laser pose and the map origin, as the kernel needs them.
struct LaserFrame {
  double x = 0.0, y = 0.0;  // laser position
  double c = 1.0, s = 0.0;  // cos, sin of its heading
  double origin_x = 0.0, origin_y = 0.0;
};

// True when this CPU runs LikelihoodPzAvx2.
bool Avx2Available();

// pz[j] = hit_terms[class of the endpoint of beam j] + rand_term for the 'count' beams of
// ranges[j] along (dir_x[j], dir_y[j]) in the laser frame; the endpoint's class as
// QuantizedDistanceField::ClassAt of (laser + range R(θ) d − origin). The arrays must be readable
// up to 'count' rounded up to a multiple of four. Needs Avx2Available().
void LikelihoodPzAvx2(const QuantizedDistanceField& classes, const double* hit_terms,
                      double rand_term, const LaserFrame& frame, const double* ranges,
                      const double* dir_x, const double* dir_y, int count, double* pz);

}  // namespace semchain::localization
