#include "localization/laser_model.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "localization/likelihood_field_avx2.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace semchain::localization {

namespace {

// The reading of beam i as the models read it: at or below the minimum range, non-finite or
// non-positive count as max range (no return), as nav2 counts them.
double UsableRange(const LaserScan& scan, std::size_t i, double range_max,
                   const AmclOptions& options) {
  const double range = scan.ranges[i];
  if (!std::isfinite(range) || range <= 0.0 ||
      (options.laser_min_range > 0.0 && range <= options.laser_min_range)) {
    return range_max;
  }
  return range;
}

// The indices of the beams to read: evenly spaced over all beams (nav2) or over the returns.
std::vector<std::size_t> BeamIndices(const LaserScan& scan, double range_max,
                                     const AmclOptions& options) {
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    if (options.beam_selection == BeamSelection::kEvenly ||
        UsableRange(scan, i, range_max, options) < range_max) {
      candidates.push_back(i);
    }
  }
  const int n = static_cast<int>(candidates.size());
  std::vector<std::size_t> indices;
  if (n == 0) return indices;
  const int step = std::max(1, (n - 1) / (options.max_beams - 1));
  for (int k = 0; k < n; k += step) indices.push_back(candidates[static_cast<std::size_t>(k)]);
  return indices;
}

}  // namespace

LaserBeams SelectBeams(const LaserScan& scan, const Pose2& laser_offset,
                       const AmclOptions& options) {
  LaserBeams beams;
  beams.laser_offset = laser_offset;
  beams.range_max = options.laser_max_range > 0.0
                        ? std::min(scan.max_range, options.laser_max_range)
                        : scan.max_range;
  for (const std::size_t i : BeamIndices(scan, beams.range_max, options)) {
    const double range = UsableRange(scan, i, beams.range_max, options);
    beams.ranges.push_back(range);
    const double bearing = scan.BeamAngle(i);
    beams.bearings.push_back(bearing);
    beams.directions.emplace_back(std::cos(bearing), std::sin(bearing));
    if (range < beams.range_max) {
      ++beams.hits;
      beams.hit_ranges.push_back(range);
      beams.hit_x.push_back(beams.directions.back().x());
      beams.hit_y.push_back(beams.directions.back().y());
    }
  }
  beams.hit_arrays = true;
  while (beams.hit_ranges.size() % 4 != 0) {
    beams.hit_ranges.push_back(0.0);
    beams.hit_x.push_back(0.0);
    beams.hit_y.push_back(0.0);
  }
  return beams;
}

namespace {

// pose ⊕ offset. A laser at the robot's origin (the corrected logs'): the composition's products
// with 0 add exactly nothing, so the result is the same without its cos and sin.
Pose2 LaserPose(const Pose2& pose, const Pose2& offset) {
  if (offset.x == 0.0 && offset.y == 0.0) return Pose2(pose.x, pose.y, pose.theta + offset.theta);
  return pose * offset;
}

// The distance class at the endpoint of a beam of the laser at 'laser' (cos, sin of its heading
// given), exactly as the scalar code finds it: cell floor((laser + range R(θ) d − origin) /
// resolution) (QuantizedDistanceField::ClassAt). With SSE2 x and y share one register; each
// lane does the scalar operations in their order (c dx + (−s) dy is c dx − s dy exactly), so
// the same doubles and the same cells.
class EndpointClasses {
 public:
  EndpointClasses(const QuantizedDistanceField& classes, const Pose2& laser, double c, double s,
                  const Eigen::Vector2d& origin)
      : classes_(classes), laser_(laser), c_(c), s_(s), origin_(origin) {
#if defined(__SSE2__)
    cs_ = _mm_set_pd(s, c);
    minus_s_c_ = _mm_set_pd(c, -s);
    laser_xy_ = _mm_set_pd(laser.y, laser.x);
    origin_xy_ = _mm_set_pd(origin.y(), origin.x());
    inverse_ = _mm_set1_pd(classes.inverse_resolution());
#endif
  }

  int ClassOf(double range, const Eigen::Vector2d& d) const {
#if defined(__SSE2__)
    const __m128d rotated =
        _mm_add_pd(_mm_mul_pd(cs_, _mm_set1_pd(d.x())), _mm_mul_pd(minus_s_c_, _mm_set1_pd(d.y())));
    const __m128d offset =
        _mm_sub_pd(_mm_add_pd(laser_xy_, _mm_mul_pd(_mm_set1_pd(range), rotated)), origin_xy_);
    const __m128d q = _mm_mul_pd(offset, inverse_);
    const __m128d truncated = _mm_cvtepi32_pd(_mm_cvttpd_epi32(q));
    const __m128d one = _mm_set1_pd(1.0);
    const __m128d floored = _mm_sub_pd(truncated, _mm_and_pd(_mm_cmplt_pd(q, truncated), one));
    const __m128d fraction = _mm_sub_pd(q, floored);
    const __m128d guard = _mm_set1_pd(QuantizedDistanceField::kBorderGuard);
    const __m128d magnitude = _mm_andnot_pd(_mm_set1_pd(-0.0), q);
    const __m128d doubtful = _mm_or_pd(
        _mm_or_pd(_mm_cmplt_pd(fraction, guard), _mm_cmpgt_pd(fraction, _mm_sub_pd(one, guard))),
        _mm_cmpnlt_pd(magnitude, _mm_set1_pd(QuantizedDistanceField::kMaxQuotient)));
    if (_mm_movemask_pd(doubtful) != 0) {  // near a cell border or far off: the exact path
      return classes_.ClassAt(_mm_cvtsd_f64(offset),
                              _mm_cvtsd_f64(_mm_unpackhi_pd(offset, offset)));
    }
    const __m128i cell = _mm_cvttpd_epi32(floored);
    return classes_.ClassOfCell(_mm_cvtsi128_si32(cell),
                                _mm_cvtsi128_si32(_mm_shuffle_epi32(cell, 1)));
#else
    return classes_.ClassAt(laser_.x + range * (c_ * d.x() - s_ * d.y()) - origin_.x(),
                            laser_.y + range * (s_ * d.x() + c_ * d.y()) - origin_.y());
#endif
  }

 private:
  const QuantizedDistanceField& classes_;
  Pose2 laser_;
  [[maybe_unused]] double c_, s_;  // read only without SSE2 (clang warns otherwise)
  Eigen::Vector2d origin_;
#if defined(__SSE2__)
  __m128d cs_, minus_s_c_, laser_xy_, origin_xy_, inverse_;
#endif
};

}  // namespace

LikelihoodFieldModel::LikelihoodFieldModel(const LocalizationMap& map, const AmclOptions& options)
    : map_(map),
      z_hit_(options.z_hit),
      z_rand_(options.z_rand),
      factor_(-0.5 / (options.sigma_hit * options.sigma_hit)) {
  for (const double d : map_.quantized_field().distances()) {
    hit_terms_.push_back(z_hit_ * std::exp(factor_ * d * d));
  }
}

double LikelihoodFieldModel::BeamLikelihood(double distance, double range_max) const {
  return z_hit_ * std::exp(factor_ * distance * distance) + z_rand_ / range_max;
}

double LikelihoodFieldModel::Weight(const LaserBeams& beams, const Pose2& pose,
                                    double* mean_beam) const {
  const QuantizedDistanceField& classes = map_.quantized_field();
  if (!classes.ok()) return WeightDirect(beams, pose, mean_beam);
  // The same arithmetic as WeightDirect, term for term (so the same weights to the last bit),
  // with exp replaced by a table look-up and DistanceField::CellOf's floor(a / resolution) by
  // a product with the inverse: the two differ by at most an ulp, so their floors differ only
  // when the product lies within a hair of an integer, and then the division is done.
  const Pose2 laser = LaserPose(pose, beams.laser_offset);
  const mapping::DistanceField& field = map_.distance_field();
  const double c = std::cos(laser.theta);
  const double s = std::sin(laser.theta);
  const double rand_term = z_rand_ / beams.range_max;
  if (Avx2Available() && beams.hit_arrays) {
    return WeightAvx2(beams, {laser.x, laser.y, c, s, field.origin().x(), field.origin().y()},
                      rand_term, mean_beam);
  }
  const EndpointClasses endpoint(classes, laser, c, s, field.origin());
  // In chunks: first every beam's pz (independent of each other), then the sums in beam order
  // (the same order of additions as before); one loop doing both keeps too many values live and
  // the running sum spills to memory.
  constexpr std::size_t kChunk = 64;
  std::array<double, kChunk> pz;
  double p = 1.0, sum = 0.0;
  int used = 0;
  const std::size_t n = beams.ranges.size();
  for (std::size_t begin = 0; begin < n; begin += kChunk) {
    const std::size_t end = std::min(n, begin + kChunk);
    std::size_t count = 0;
    for (std::size_t i = begin; i < end; ++i) {
      const double range = beams.ranges[i];
      if (range >= beams.range_max) continue;
      const Eigen::Vector2d& d = beams.directions[i];
      pz[count++] = hit_terms_[static_cast<std::size_t>(endpoint.ClassOf(range, d))] + rand_term;
    }
    for (std::size_t j = 0; j < count; ++j) {
      p += pz[j] * pz[j] * pz[j];
      sum += pz[j];
    }
    used += static_cast<int>(count);
  }
  *mean_beam = used > 0 ? sum / used : 0.0;
  return p;
}

void LikelihoodFieldModel::Weight4(const LaserBeams& beams,
                                   const std::array<const Pose2*, 4>& poses,
                                   std::array<double, 4>* weights,
                                   std::array<double, 4>* mean_beams) const {
  if (!(map_.quantized_field().ok() && Avx2Available() && beams.hit_arrays)) {
    LaserModel::Weight4(beams, poses, weights, mean_beams);
    return;
  }
  const mapping::DistanceField& field = map_.distance_field();
  std::array<LaserFrame, 4> frames;
  for (std::size_t i = 0; i < 4; ++i) {
    const Pose2 laser = LaserPose(*poses[i], beams.laser_offset);
    frames[i] = {laser.x,
                 laser.y,
                 std::cos(laser.theta),
                 std::sin(laser.theta),
                 field.origin().x(),
                 field.origin().y()};
  }
  const double rand_term = z_rand_ / beams.range_max;
  constexpr int kChunk = 64;
  std::array<std::array<double, kChunk>, 4> pz;
  std::array<double, 4> p = {1.0, 1.0, 1.0, 1.0}, sum = {0.0, 0.0, 0.0, 0.0};
  const int n = beams.hits;
  for (int begin = 0; begin < n; begin += kChunk) {
    const int count = std::min(kChunk, n - begin);
    for (std::size_t i = 0; i < 4; ++i) {
      LikelihoodPzAvx2(map_.quantized_field(), hit_terms_.data(), rand_term, frames[i],
                       beams.hit_ranges.data() + begin, beams.hit_x.data() + begin,
                       beams.hit_y.data() + begin, count, pz[i].data());
    }
    for (int j = 0; j < count; ++j) {  // beam order within each sum, as Weight adds them
      for (std::size_t i = 0; i < 4; ++i) {
        p[i] += pz[i][j] * pz[i][j] * pz[i][j];
        sum[i] += pz[i][j];
      }
    }
  }
  for (std::size_t i = 0; i < 4; ++i) {
    (*weights)[i] = p[i];
    (*mean_beams)[i] = n > 0 ? sum[i] / n : 0.0;
  }
}

double LikelihoodFieldModel::WeightAvx2(const LaserBeams& beams, const LaserFrame& frame,
                                        double rand_term, double* mean_beam) const {
  constexpr int kChunk = 64;
  std::array<double, kChunk> pz;
  double p = 1.0, sum = 0.0;
  const int n = beams.hits;
  for (int begin = 0; begin < n; begin += kChunk) {
    const int count = std::min(kChunk, n - begin);
    LikelihoodPzAvx2(map_.quantized_field(), hit_terms_.data(), rand_term, frame,
                     beams.hit_ranges.data() + begin, beams.hit_x.data() + begin,
                     beams.hit_y.data() + begin, count, pz.data());
    for (int j = 0; j < count; ++j) {  // beam order, as the reference code adds them
      p += pz[j] * pz[j] * pz[j];
      sum += pz[j];
    }
  }
  *mean_beam = n > 0 ? sum / n : 0.0;
  return p;
}

double LikelihoodFieldModel::WeightDirect(const LaserBeams& beams, const Pose2& pose,
                                          double* mean_beam) const {
  const Pose2 laser = pose * beams.laser_offset;
  const mapping::DistanceField& field = map_.distance_field();
  const double c = std::cos(laser.theta);
  const double s = std::sin(laser.theta);
  double p = 1.0, sum = 0.0;
  int used = 0;
  for (std::size_t i = 0; i < beams.ranges.size(); ++i) {
    const double range = beams.ranges[i];
    if (range >= beams.range_max) continue;
    const Eigen::Vector2d& d = beams.directions[i];
    const Eigen::Vector2d hit(laser.x + range * (c * d.x() - s * d.y()),
                              laser.y + range * (s * d.x() + c * d.y()));
    const double pz = BeamLikelihood(field.DistanceAt(hit), beams.range_max);
    p += pz * pz * pz;
    sum += pz;
    ++used;
  }
  *mean_beam = used > 0 ? sum / used : 0.0;
  return p;
}

BeamModel::BeamModel(const LocalizationMap& map, const AmclOptions& options)
    : map_(map), options_(options) {}

double BeamModel::BeamLikelihood(double range, double expected, double range_max) const {
  const double z = range - expected;
  double pz = options_.z_hit * std::exp(-(z * z) / (2.0 * options_.sigma_hit * options_.sigma_hit));
  if (z < 0.0) {
    pz += options_.z_short * options_.lambda_short * std::exp(-options_.lambda_short * range);
  }
  // As nav2: z_max only for a reading of exactly range_max, z_rand only below it; a reading
  // beyond range_max (CARMEN's 81.91 "no return" above an 80.99 m maximum) gets neither.
  if (range == range_max) pz += options_.z_max;
  if (range < range_max) pz += options_.z_rand / range_max;
  return pz;
}

double BeamModel::Weight(const LaserBeams& beams, const Pose2& pose, double* mean_beam) const {
  const Pose2 laser = pose * beams.laser_offset;
  double p = 1.0, sum = 0.0;
  for (std::size_t i = 0; i < beams.ranges.size(); ++i) {
    const double expected =
        map_.CalcRange(laser.translation(), laser.theta + beams.bearings[i], beams.range_max);
    const double pz = BeamLikelihood(beams.ranges[i], expected, beams.range_max);
    p += pz * pz * pz;
    sum += pz;
  }
  *mean_beam = beams.ranges.empty() ? 0.0 : sum / static_cast<double>(beams.ranges.size());
  return p;
}

std::unique_ptr<LaserModel> MakeLaserModel(const LocalizationMap& map, const AmclOptions& options) {
  if (options.laser_model_type == LaserModelType::kBeam) {
    return std::make_unique<BeamModel>(map, options);
  }
  return std::make_unique<LikelihoodFieldModel>(map, options);
}

}  // namespace semchain::localization
