#include "localization/likelihood_field_avx2.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define SEMCHAIN_HAVE_AVX2_KERNEL 1
#endif

namespace semchain::localization {
namespace {

// The scalar path: the same expression as the model's reference code.
double ScalarPz(const QuantizedDistanceField& classes, const double* hit_terms, double rand_term,
                const LaserFrame& f, double range, double dx, double dy) {
  const int k = classes.ClassAt(f.x + range * (f.c * dx - f.s * dy) - f.origin_x,
                                f.y + range * (f.s * dx + f.c * dy) - f.origin_y);
  return hit_terms[k] + rand_term;
}

}  // namespace

#if defined(SEMCHAIN_HAVE_AVX2_KERNEL)

bool Avx2Available() {
  static const bool available = __builtin_cpu_supports("avx2");
  return available;
}

namespace {

// Lanes near a cell border (the product with the inverse resolution may floor differently from
// the division) or far off the map: the scalar exact path decides them.
__attribute__((target("avx2"))) inline __m256d Doubtful(__m256d q, __m256d floored, __m256d guard,
                                                        __m256d upper, __m256d sign,
                                                        __m256d max_quotient) {
  const __m256d fraction = _mm256_sub_pd(q, floored);
  return _mm256_or_pd(_mm256_or_pd(_mm256_cmp_pd(fraction, guard, _CMP_LT_OQ),
                                   _mm256_cmp_pd(fraction, upper, _CMP_GT_OQ)),
                      _mm256_cmp_pd(_mm256_andnot_pd(sign, q), max_quotient, _CMP_NLT_UQ));
}

}  // namespace

__attribute__((target("avx2"))) void LikelihoodPzAvx2(const QuantizedDistanceField& classes,
                                                      const double* hit_terms, double rand_term,
                                                      const LaserFrame& f, const double* ranges,
                                                      const double* dir_x, const double* dir_y,
                                                      int count, double* pz) {
  const __m256d c = _mm256_set1_pd(f.c), s = _mm256_set1_pd(f.s);
  const __m256d laser_x = _mm256_set1_pd(f.x), laser_y = _mm256_set1_pd(f.y);
  const __m256d origin_x = _mm256_set1_pd(f.origin_x), origin_y = _mm256_set1_pd(f.origin_y);
  const __m256d inverse = _mm256_set1_pd(classes.inverse_resolution());
  const __m256d guard = _mm256_set1_pd(QuantizedDistanceField::kBorderGuard);
  const __m256d upper = _mm256_set1_pd(1.0 - QuantizedDistanceField::kBorderGuard);
  const __m256d max_quotient = _mm256_set1_pd(QuantizedDistanceField::kMaxQuotient);
  const __m256d sign = _mm256_set1_pd(-0.0);
  const __m128i width = _mm_set1_epi32(classes.width());
  const __m128i height = _mm_set1_epi32(classes.height());
  const __m128i minus_one = _mm_set1_epi32(-1);
  const int off_map = classes.off_map();
  // Whole groups of four: the arrays are padded to a multiple of four, and the pz of padding
  // lanes are computed but not kept.
  alignas(32) double group_pz[4];
  alignas(16) int group_index[4];
  alignas(16) int group_inside[4];
  for (int j = 0; j < count; j += 4) {
    const __m256d range = _mm256_loadu_pd(ranges + j);
    const __m256d dx = _mm256_loadu_pd(dir_x + j);
    const __m256d dy = _mm256_loadu_pd(dir_y + j);
    const __m256d rotated_x = _mm256_sub_pd(_mm256_mul_pd(c, dx), _mm256_mul_pd(s, dy));
    const __m256d rotated_y = _mm256_add_pd(_mm256_mul_pd(s, dx), _mm256_mul_pd(c, dy));
    const __m256d x =
        _mm256_sub_pd(_mm256_add_pd(laser_x, _mm256_mul_pd(range, rotated_x)), origin_x);
    const __m256d y =
        _mm256_sub_pd(_mm256_add_pd(laser_y, _mm256_mul_pd(range, rotated_y)), origin_y);
    const __m256d qx = _mm256_mul_pd(x, inverse);
    const __m256d qy = _mm256_mul_pd(y, inverse);
    const __m256d fx = _mm256_floor_pd(qx);
    const __m256d fy = _mm256_floor_pd(qy);
    const int redo =
        _mm256_movemask_pd(_mm256_or_pd(Doubtful(qx, fx, guard, upper, sign, max_quotient),
                                        Doubtful(qy, fy, guard, upper, sign, max_quotient)));
    const __m128i ix = _mm256_cvttpd_epi32(fx);
    const __m128i iy = _mm256_cvttpd_epi32(fy);
    const __m128i inside =
        _mm_and_si128(_mm_and_si128(_mm_cmpgt_epi32(ix, minus_one), _mm_cmpgt_epi32(width, ix)),
                      _mm_and_si128(_mm_cmpgt_epi32(iy, minus_one), _mm_cmpgt_epi32(height, iy)));
    _mm_store_si128(reinterpret_cast<__m128i*>(group_index),
                    _mm_add_epi32(_mm_mullo_epi32(iy, width), ix));
    _mm_store_si128(reinterpret_cast<__m128i*>(group_inside), inside);
    // Scalar loads: four of them cost less than two gathers on the CPUs we run on.
    for (int lane = 0; lane < 4; ++lane) {
      const int k = group_inside[lane] != 0 ? classes.AtIndex(group_index[lane]) : off_map;
      group_pz[lane] = hit_terms[k] + rand_term;
    }
    const int kept = count - j < 4 ? count - j : 4;
    for (int lane = 0; lane < kept; ++lane) {
      pz[j + lane] = (redo >> lane) & 1
                         ? ScalarPz(classes, hit_terms, rand_term, f, ranges[j + lane],
                                    dir_x[j + lane], dir_y[j + lane])
                         : group_pz[lane];
    }
  }
}

#else

bool Avx2Available() { return false; }

void LikelihoodPzAvx2(const QuantizedDistanceField& classes, const double* hit_terms,
                      double rand_term, const LaserFrame& f, const double* ranges,
                      const double* dir_x, const double* dir_y, int count, double* pz) {
  for (int j = 0; j < count; ++j) {
    pz[j] = ScalarPz(classes, hit_terms, rand_term, f, ranges[j], dir_x[j], dir_y[j]);
  }
}

#endif

}  // namespace semchain::localization
