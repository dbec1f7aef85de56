#include "semantic/object_association.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <optional>

namespace semchain::semantic {
namespace {

// 'polygon' relative to 'origin', in single precision for OpenCV (relative, so that maps far
// from their origin keep millimetres).
std::vector<cv::Point2f> ToCv(const std::vector<Eigen::Vector2d>& polygon,
                              const Eigen::Vector2d& origin) {
  std::vector<cv::Point2f> points;
  points.reserve(polygon.size());
  for (const Eigen::Vector2d& p : polygon) {
    points.emplace_back(static_cast<float>(p.x() - origin.x()),
                        static_cast<float>(p.y() - origin.y()));
  }
  return points;
}

double Area(const std::vector<Eigen::Vector2d>& polygon) {
  if (polygon.size() < 3) return 0.0;
  return cv::contourArea(ToCv(polygon, polygon.front()));
}

// The radius of the circle about 'shape.center' that holds its footprint.
double Reach(const FittedShape& shape) {
  double reach = 0.0;
  for (const Eigen::Vector2d& p : shape.footprint) {
    reach = std::max(reach, (p - shape.center).norm());
  }
  return reach;
}

}  // namespace

int FramesTogether(const ObjectPart& a, const ObjectPart& b) {
  int together = 0;
  for (int frame : a.frames) together += static_cast<int>(b.frames.count(frame));
  return together;
}

bool SeenAsTwo(int together, int seen, const ObjectExtractionOptions& options) {
  return together >= options.min_split_frames &&
         static_cast<double>(together) >= options.min_split_share * static_cast<double>(seen);
}

bool PartsSeenAsTwo(const ObjectPart& a, const ObjectPart& b,
                    const ObjectExtractionOptions& options) {
  const int together = FramesTogether(a, b);
  const int seen = static_cast<int>(a.frames.size() + b.frames.size()) - together;
  return SeenAsTwo(together, seen, options);
}

double PartExtent(const ObjectPart& part, double resolution) {
  if (part.cells.empty()) return 0.0;
  std::vector<cv::Point2f> centers;
  centers.reserve(part.cells.size());
  for (const Eigen::Vector2i& cell : part.cells) {
    centers.emplace_back(static_cast<float>(cell.x()), static_cast<float>(cell.y()));
  }
  const cv::RotatedRect box = cv::minAreaRect(centers);
  // Cell centres span one cell less than the cells do.
  return (std::max(box.size.width, box.size.height) + 1.0) * resolution;
}

std::vector<ObjectPart> MergeFragments(std::vector<ObjectPart> parts, const ClassShapePrior& prior,
                                       double resolution, const ObjectExtractionOptions& options) {
  const long limit = static_cast<long>(options.merge_gap_cells) * options.merge_gap_cells;
  const auto near = [limit](const ObjectPart& a, const ObjectPart& b) {
    for (const Eigen::Vector2i& p : a.cells) {
      for (const Eigen::Vector2i& q : b.cells) {
        if ((p - q).cast<long>().squaredNorm() <= limit) return true;
      }
    }
    return false;
  };
  const double fragment = options.fragment_fraction * prior.Extent();
  bool merged = true;
  while (merged) {
    merged = false;
    for (std::size_t i = 0; i < parts.size() && !merged; ++i) {
      for (std::size_t j = i + 1; j < parts.size() && !merged; ++j) {
        if (PartsSeenAsTwo(parts[i], parts[j], options)) continue;
        if (std::min(PartExtent(parts[i], resolution), PartExtent(parts[j], resolution)) >=
                fragment ||
            !near(parts[i], parts[j])) {
          continue;
        }
        parts[i].cells.insert(parts[i].cells.end(), parts[j].cells.begin(), parts[j].cells.end());
        parts[i].frames.insert(parts[j].frames.begin(), parts[j].frames.end());
        parts[i].members.insert(parts[i].members.end(), parts[j].members.begin(),
                                parts[j].members.end());
        parts.erase(parts.begin() + static_cast<long>(j));
        merged = true;
      }
    }
  }
  return parts;
}

double OverlapArea(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b) {
  if (a.size() < 3 || b.size() < 3) return 0.0;
  std::vector<cv::Point2f> intersection;
  return std::max(
      0.0f, cv::intersectConvexConvex(ToCv(a, a.front()), ToCv(b, a.front()), intersection, true));
}

namespace {

// The overlap of two footprints as a fraction of the smaller one's area (0 when either is
// degenerate).
double OverlapOfSmaller(const FittedShape& a, const FittedShape& b) {
  if ((a.center - b.center).norm() >= Reach(a) + Reach(b)) return 0.0;
  const double smaller = std::min(Area(a.footprint), Area(b.footprint));
  return smaller > 0.0 ? OverlapArea(a.footprint, b.footprint) / smaller : 0.0;
}

}  // namespace

bool SameObject(const FittedShape& a, const FittedShape& b, bool seen_as_two,
                const ClassShapePrior& prior, const ObjectExtractionOptions& options) {
  // Two detections in the same frames: the detector saw two objects.
  if (seen_as_two) return false;
  if ((a.center - b.center).norm() < options.merge_center_fraction * prior.HalfDiagonal()) {
    return true;
  }
  return OverlapOfSmaller(a, b) >= options.merge_overlap;
}

std::vector<FittedPart> AssociateParts(std::vector<ObjectPart> parts,
                                       const std::function<FittedShape(const ObjectPart&)>& fit,
                                       const ClassShapePrior& prior,
                                       const ObjectExtractionOptions& options) {
  std::vector<FittedPart> fitted;
  fitted.reserve(parts.size());
  for (ObjectPart& part : parts) {
    FittedShape shape = fit(part);
    fitted.push_back({std::move(part), std::move(shape)});
  }
  while (true) {
    std::size_t best_i = 0;
    std::size_t best_j = 0;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < fitted.size(); ++i) {
      for (std::size_t j = i + 1; j < fitted.size(); ++j) {
        const double distance = (fitted[i].shape.center - fitted[j].shape.center).norm();
        if (distance >= best) continue;
        if (SameObject(fitted[i].shape, fitted[j].shape,
                       PartsSeenAsTwo(fitted[i].part, fitted[j].part, options), prior, options)) {
          best = distance;
          best_i = i;
          best_j = j;
        }
      }
    }
    if (!std::isfinite(best)) break;
    ObjectPart& kept = fitted[best_i].part;
    ObjectPart& joined = fitted[best_j].part;
    kept.cells.insert(kept.cells.end(), joined.cells.begin(), joined.cells.end());
    kept.frames.insert(joined.frames.begin(), joined.frames.end());
    kept.members.insert(kept.members.end(), joined.members.begin(), joined.members.end());
    fitted[best_i].shape = fit(kept);
    fitted.erase(fitted.begin() + static_cast<long>(best_j));
  }
  return AbsorbFragments(std::move(fitted), prior, options);
}

std::vector<FittedPart> AbsorbFragments(std::vector<FittedPart> fitted,
                                        const ClassShapePrior& prior,
                                        const ObjectExtractionOptions& options) {
  if (!options.absorb_fragments) return fitted;
  const double fragment = options.fragment_fraction * prior.Extent();
  const double reach = 2.0 * options.merge_center_fraction * prior.HalfDiagonal();
  const auto is_fragment = [&](const FittedPart& p) { return ShapeExtent(p.shape) < fragment; };
  std::vector<bool> absorbed(fitted.size(), false);
  for (std::size_t f = 0; f < fitted.size(); ++f) {
    if (!is_fragment(fitted[f])) continue;
    std::optional<std::size_t> nearest;
    double best = reach;
    for (std::size_t k = 0; k < fitted.size(); ++k) {
      // Only whole parts take pieces in (an absorbed part was itself a piece).
      if (k == f || is_fragment(fitted[k])) continue;
      const double distance = (fitted[f].shape.center - fitted[k].shape.center).norm();
      if (distance < best && !PartsSeenAsTwo(fitted[f].part, fitted[k].part, options)) {
        best = distance;
        nearest = k;
      }
    }
    if (!nearest) continue;
    ObjectPart& object = fitted[*nearest].part;
    object.frames.insert(fitted[f].part.frames.begin(), fitted[f].part.frames.end());
    object.members.insert(object.members.end(), fitted[f].part.members.begin(),
                          fitted[f].part.members.end());
    absorbed[f] = true;
  }
  std::vector<FittedPart> kept;
  for (std::size_t k = 0; k < fitted.size(); ++k) {
    if (!absorbed[k]) kept.push_back(std::move(fitted[k]));
  }
  return kept;
}

namespace {

// Whether 'a' is the stronger name of the object: seen in more frames, then on more cells.
bool Outweighs(const ObjectPart& a, const ObjectPart& b) {
  if (a.frames.size() != b.frames.size()) return a.frames.size() > b.frames.size();
  return a.cells.size() >= b.cells.size();
}

}  // namespace

namespace {

// The overlap of two parts' footprints (fraction of the smaller) when they are one object named
// two ways (OneObjectTwoNames), else nothing.
std::optional<double> NameConflictOverlap(const ClassedPart& a, const ClassedPart& b,
                                          const ObjectExtractionOptions& options) {
  if (a.class_id == b.class_id || options.merge_across_classes > 1.0 ||
      PartsSeenAsTwo(a.fitted.part, b.fitted.part, options)) {
    return std::nullopt;
  }
  const double overlap = OverlapOfSmaller(a.fitted.shape, b.fitted.shape);
  if (overlap < options.merge_across_classes) return std::nullopt;
  return overlap;
}

}  // namespace

bool OneObjectTwoNames(const ClassedPart& a, const ClassedPart& b,
                       const ObjectExtractionOptions& options) {
  return NameConflictOverlap(a, b, options).has_value();
}

std::vector<std::size_t> ResolveClassConflicts(const std::vector<ClassedPart>& parts,
                                               const ObjectExtractionOptions& options) {
  // Nothing is refitted, so the overlaps are known at the start: the pairs, largest overlap
  // first (ties in index order), each decided unless one of its parts was dropped already.
  struct Conflict {
    double overlap;
    std::size_t i;
    std::size_t j;
  };
  std::vector<Conflict> conflicts;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    for (std::size_t j = i + 1; j < parts.size(); ++j) {
      if (const std::optional<double> overlap = NameConflictOverlap(parts[i], parts[j], options)) {
        conflicts.push_back({*overlap, i, j});
      }
    }
  }
  std::stable_sort(conflicts.begin(), conflicts.end(),
                   [](const Conflict& a, const Conflict& b) { return a.overlap > b.overlap; });
  std::vector<bool> dropped(parts.size(), false);
  for (const Conflict& conflict : conflicts) {
    if (dropped[conflict.i] || dropped[conflict.j]) continue;
    const bool i_wins = Outweighs(parts[conflict.i].fitted.part, parts[conflict.j].fitted.part);
    dropped[i_wins ? conflict.j : conflict.i] = true;
  }
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (!dropped[i]) kept.push_back(i);
  }
  return kept;
}

}  // namespace semchain::semantic
