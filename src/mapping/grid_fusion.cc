#include "mapping/grid_fusion.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.h"

namespace semchain::mapping {
namespace {

std::uint16_t SaturatingSum(std::uint16_t a, std::uint16_t b) {
  return static_cast<std::uint16_t>(
      std::min<int>(std::numeric_limits<std::uint16_t>::max(), int{a} + int{b}));
}

// The probability of a cell for eq. 10: 0.5 where unknown (no evidence), else clamped.
double CellProbability(const GridCell* cell, const GridFusionOptions& options) {
  if (cell == nullptr || !cell->Known()) return 0.5;
  return std::clamp(LogOddsToProbability(cell->log_odds), options.min_probability,
                    options.max_probability);
}

// The box of 'from' cells expressed as cells of 'to' (which shares its resolution).
CellBox BoundsIn(const OccupancyGrid& from, const OccupancyGrid& to) {
  const CellBox box = from.KnownBounds();
  if (box.empty()) return box;
  return {to.CellOf(from.CellCenter(box.min)), to.CellOf(from.CellCenter(box.max))};
}

}  // namespace

bool GridFusionOptions::Validate(std::string* error) const {
  if (!(min_probability > 0.0 && min_probability <= 0.5 && max_probability >= 0.5 &&
        max_probability < 1.0)) {
    *error = "need 0 < min_probability <= 0.5 <= max_probability < 1";
    return false;
  }
  return true;
}

double FuseProbabilities(double p_a, double p_b, const GridFusionOptions& options) {
  const double a = std::clamp(p_a, options.min_probability, options.max_probability);
  const double b = std::clamp(p_b, options.min_probability, options.max_probability);
  return a * b / (a * b + (1.0 - a) * (1.0 - b));  // eq. 10
}

OccupancyGrid FuseGrids(const OccupancyGrid& a, const OccupancyGrid& b,
                        const GridFusionOptions& options) {
  SEMCHAIN_CHECK(std::abs(a.resolution() - b.resolution()) < 1e-9);
  OccupancyGrid fused(a.options(), a.origin());
  CellBox box = a.KnownBounds();
  const CellBox b_box = BoundsIn(b, a);
  if (box.empty()) {
    box = b_box;
  } else if (!b_box.empty()) {
    box = {box.min.cwiseMin(b_box.min), box.max.cwiseMax(b_box.max)};
  }
  const double limit = a.options().max_abs_log_odds;
  for (int y = box.min.y(); y <= box.max.y(); ++y) {
    for (int x = box.min.x(); x <= box.max.x(); ++x) {
      const Eigen::Vector2i cell(x, y);
      const GridCell* in_a = a.Find(cell);
      const GridCell* in_b = b.Find(b.CellOf(a.CellCenter(cell)));
      const bool known_a = in_a != nullptr && in_a->Known();
      const bool known_b = in_b != nullptr && in_b->Known();
      if (!known_a && !known_b) continue;
      // Eq. 10 evaluated in log-odds form: logit(P) = logit(P_a) + logit(P_b).
      const double p = FuseProbabilities(CellProbability(in_a, options),
                                         CellProbability(in_b, options), options);
      GridCell out;
      out.log_odds = static_cast<float>(std::clamp(ProbabilityToLogOdds(p), -limit, limit));
      out.hits = SaturatingSum(known_a ? in_a->hits : 0, known_b ? in_b->hits : 0);
      out.observations =
          SaturatingSum(known_a ? in_a->observations : 0, known_b ? in_b->observations : 0);
      // Keep the sub-cell endpoint mean of whichever grid saw returns here (a's first).
      const GridCell* source = known_a && in_a->hits > 0 ? in_a : (known_b ? in_b : nullptr);
      if (source != nullptr && source->hits > 0) {
        out.mean_x = source->mean_x;
        out.mean_y = source->mean_y;
      }
      fused.SetCell(cell, out);
    }
  }
  return fused;
}

}  // namespace semchain::mapping
