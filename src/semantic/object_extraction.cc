#include "semantic/object_extraction.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "semantic/object_association.h"
#include "semantic/shape_fit.h"

namespace semchain::semantic {
namespace {

double LogitOf(double probability) { return std::log(probability / (1.0 - probability)); }

cv::Mat ClassMask(const SemanticGrid& grid, int c, double threshold) {
  cv::Mat mask;
  cv::compare(grid.log_odds(c), threshold, mask, cv::CMP_GT);  // 255 where above
  return mask;
}

void Morphology(cv::Mat& mask, int operation, int kernel_size) {
  if (kernel_size <= 1) return;
  const cv::Mat kernel =
      cv::getStructuringElement(cv::MORPH_RECT, cv::Size(kernel_size, kernel_size));
  cv::morphologyEx(mask, mask, operation, kernel);
}

// Cells of 'labels' equal to 'label', in raster order.
std::vector<Eigen::Vector2i> CellsWithLabel(const cv::Mat& labels, int label) {
  std::vector<Eigen::Vector2i> cells;
  for (int y = 0; y < labels.rows; ++y) {
    const int* row = labels.ptr<int>(y);
    for (int x = 0; x < labels.cols; ++x) {
      if (row[x] == label) cells.emplace_back(x, y);
    }
  }
  return cells;
}

// How many of 'observation's cells carry 'label'.
int Overlap(const DetectionObservation& observation, const cv::Mat& labels, int label) {
  int count = 0;
  for (const Eigen::Vector2i& cell : observation.cells) {
    if (cell.x() >= 0 && cell.y() >= 0 && cell.x() < labels.cols && cell.y() < labels.rows &&
        labels.at<int>(cell.y(), cell.x()) == label) {
      ++count;
    }
  }
  return count;
}

bool IsOn(const DetectionObservation& observation, const cv::Mat& labels, int label,
          double fraction) {
  return !observation.cells.empty() && Overlap(observation, labels, label) >=
                                           fraction * static_cast<double>(observation.cells.size());
}

Eigen::Vector2d MeanCell(const std::vector<Eigen::Vector2i>& cells) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2i& cell : cells) sum += cell.cast<double>();
  return cells.empty() ? sum : Eigen::Vector2d(sum / static_cast<double>(cells.size()));
}

// Splits the cells of one region among the k objects on it. The k detections of a frame that
// saw them all seed k-means on the cell positions.
std::vector<int> SplitRegion(const std::vector<Eigen::Vector2i>& cells,
                             const std::vector<const DetectionObservation*>& seeds) {
  const int k = static_cast<int>(seeds.size());
  std::vector<Eigen::Vector2d> centers;
  for (const DetectionObservation* seed : seeds) centers.push_back(MeanCell(seed->cells));
  cv::Mat samples(static_cast<int>(cells.size()), 2, CV_32F);
  cv::Mat labels(static_cast<int>(cells.size()), 1, CV_32S);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    samples.at<float>(static_cast<int>(i), 0) = static_cast<float>(cells[i].x());
    samples.at<float>(static_cast<int>(i), 1) = static_cast<float>(cells[i].y());
    int best = 0;
    for (int j = 1; j < k; ++j) {
      if ((cells[i].cast<double>() - centers[j]).squaredNorm() <
          (cells[i].cast<double>() - centers[best]).squaredNorm()) {
        best = j;
      }
    }
    labels.at<int>(static_cast<int>(i)) = best;
  }
  // Starting from the seeds' labels, k-means is deterministic (no random centres).
  cv::Mat centers_out;
  cv::kmeans(samples, k, labels,
             cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 1e-3), 1,
             cv::KMEANS_USE_INITIAL_LABELS, centers_out);
  return std::vector<int>(labels.begin<int>(), labels.end<int>());
}

// Centres of the cells of 'mask' within 'radius' of the centroid of 'points'.
std::vector<Eigen::Vector2d> MaskCellsNear(const cv::Mat& mask, const GridGeometry& geometry,
                                           const std::vector<Eigen::Vector2d>& points,
                                           double radius) {
  std::vector<Eigen::Vector2d> cells;
  if (mask.empty() || points.empty()) return cells;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  const Eigen::Vector2i low = geometry.CellOf(centroid - Eigen::Vector2d::Constant(radius));
  const Eigen::Vector2i high = geometry.CellOf(centroid + Eigen::Vector2d::Constant(radius));
  for (int y = std::max(0, low.y()); y <= std::min(geometry.height - 1, high.y()); ++y) {
    for (int x = std::max(0, low.x()); x <= std::min(geometry.width - 1, high.x()); ++x) {
      if (!mask.at<std::uint8_t>(y, x)) continue;
      const Eigen::Vector2d center = geometry.CenterOf({x, y});
      if ((center - centroid).norm() <= radius) cells.push_back(center);
    }
  }
  return cells;
}

// Joins regions that single detections span: one detection sees one object, so two regions
// that several detections cover at once are two faces of it (a cabinet's front and side meet
// at a corner the grid may not fill). Relabels 'labels' in place; returns the new label count.
int JoinBridgedRegions(const std::vector<const DetectionObservation*>& observations, int components,
                       const ObjectExtractionOptions& options, cv::Mat& labels) {
  std::vector<int> parent(components);
  for (int i = 0; i < components; ++i) parent[i] = i;
  const auto find = [&parent](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::map<std::pair<int, int>, int> bridges;
  for (const DetectionObservation* observation : observations) {
    std::map<int, int> histogram;
    for (const Eigen::Vector2i& cell : observation->cells) {
      if (cell.x() < 0 || cell.y() < 0 || cell.x() >= labels.cols || cell.y() >= labels.rows)
        continue;
      const int label = labels.at<int>(cell.y(), cell.x());
      if (label > 0) ++histogram[label];
    }
    std::vector<int> spanned;
    for (const auto& [label, cells] : histogram) {
      if (cells >= options.min_cells &&
          cells >= options.bridge_fraction * static_cast<double>(observation->cells.size())) {
        spanned.push_back(label);
      }
    }
    for (std::size_t i = 0; i < spanned.size(); ++i) {
      for (std::size_t j = i + 1; j < spanned.size(); ++j) ++bridges[{spanned[i], spanned[j]}];
    }
  }
  for (const auto& [pair, count] : bridges) {
    if (count >= options.min_bridges) parent[find(pair.first)] = find(pair.second);
  }
  std::vector<int> relabel(components, 0);
  int next = 1;
  for (int i = 1; i < components; ++i) {
    if (find(i) == i) relabel[i] = next++;
  }
  for (int y = 0; y < labels.rows; ++y) {
    int* row = labels.ptr<int>(y);
    for (int x = 0; x < labels.cols; ++x) row[x] = row[x] > 0 ? relabel[find(row[x])] : 0;
  }
  return next;
}

// The class's shape fitted to the part's cells (their mean points, weighted by the frames
// that hit them), completed behind the side it was seen from (in front of it on a wall) and
// kept off the free space.
FittedShape FitPart(const SemanticGrid& grid, int c, const ObjectPart& part,
                    const ClassShapePrior& prior, const LaserMapCells& laser_map) {
  std::vector<Eigen::Vector2d> points;
  std::vector<double> weights;
  Eigen::Vector2d view = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2i& cell : part.cells) {
    points.push_back(grid.MeanPoint(c, cell));
    weights.push_back(std::max(1, grid.HitFrames(c, cell)));
    view += grid.ViewDirection(c, cell);
  }
  if (view.norm() > 1e-9) view.normalize();
  const double radius = prior.Extent() + 0.2;
  return FitShape(points, weights, view, prior,
                  MaskCellsNear(laser_map.free, grid.geometry(), points, radius),
                  MaskCellsNear(laser_map.occupied, grid.geometry(), points,
                                0.5 * prior.Extent() + kFaceWallReach + 0.2));
}

// A class's evidence above the threshold and its regions: the evidence closed and opened,
// labelled by connected components, those the detections bridge joined.
struct ClassRegions {
  cv::Mat evidence;  // CV_8U, 255 where the class's evidence is above the threshold
  cv::Mat labels;    // CV_32S, regions 1 .. count - 1 (0: none)
  int count = 0;
};

ClassRegions FindClassRegions(const SemanticGrid& grid, int c, double threshold,
                              const std::vector<const DetectionObservation*>& of_class,
                              const ObjectExtractionOptions& o) {
  ClassRegions regions;
  regions.evidence = ClassMask(grid, c, threshold);
  cv::Mat mask = regions.evidence.clone();
  Morphology(mask, cv::MORPH_CLOSE, o.closing_kernel);
  Morphology(mask, cv::MORPH_OPEN, o.opening_kernel);
  const int components = cv::connectedComponents(mask, regions.labels, 8, CV_32S);
  regions.count = JoinBridgedRegions(of_class, components, o, regions.labels);
  return regions;
}

using DetectionsByFrame = std::map<int, std::vector<const DetectionObservation*>>;

// The detections of the class on region 'label', by frame.
DetectionsByFrame DetectionsOnRegion(const std::vector<const DetectionObservation*>& of_class,
                                     const cv::Mat& labels, int label,
                                     const ObjectExtractionOptions& o) {
  DetectionsByFrame by_frame;
  for (const DetectionObservation* observation : of_class) {
    if (IsOn(*observation, labels, label, o.detection_overlap)) {
      by_frame[observation->frame].push_back(observation);
    }
  }
  return by_frame;
}

// The part (0 .. *parts - 1) of each of the region's cells: one part, or k when the frames
// that saw k objects on the region at once show k objects there (SeenAsTwo), split around the
// detections of the frame with exactly k there whose detections cover most cells.
std::vector<int> SplitAmongObjects(const std::vector<Eigen::Vector2i>& region,
                                   const DetectionsByFrame& by_frame,
                                   const ObjectExtractionOptions& o, int* parts) {
  // k = the most objects that enough frames saw on the region at once: the k of the n-th most
  // crowded frame, n the fewest frames SeenAsTwo accepts.
  std::vector<int> per_frame;
  for (const auto& [frame, list] : by_frame) per_frame.push_back(static_cast<int>(list.size()));
  std::sort(per_frame.rbegin(), per_frame.rend());
  const int seen = static_cast<int>(per_frame.size());
  int needed = std::max(o.min_split_frames, 1);
  while (needed <= seen && !SeenAsTwo(needed, seen, o)) ++needed;
  const int k = needed <= seen ? per_frame[static_cast<std::size_t>(needed - 1)] : 1;
  std::vector<int> assignment(region.size(), 0);
  *parts = 1;
  if (k <= 1) return assignment;
  // Seeds: the frame with exactly k detections here whose detections cover most cells.
  const std::vector<const DetectionObservation*>* seeds = nullptr;
  std::size_t best_cells = 0;
  for (const auto& [frame, list] : by_frame) {
    if (static_cast<int>(list.size()) != k) continue;
    std::size_t total = 0;
    for (const DetectionObservation* observation : list) total += observation->cells.size();
    if (total > best_cells) {
      best_cells = total;
      seeds = &list;
    }
  }
  if (seeds != nullptr) {
    assignment = SplitRegion(region, *seeds);
    *parts = k;
  }
  return assignment;
}

// One object part per part of the region, from the cells that carry evidence (closing only
// joined them), with the class's detections on it.
void AddRegionPieces(const std::vector<Eigen::Vector2i>& region, const std::vector<int>& assignment,
                     int parts, const cv::Mat& evidence,
                     const std::vector<DetectionObservation>& observations, int c,
                     const ObjectExtractionOptions& o, std::vector<ObjectPart>* pieces) {
  cv::Mat part_labels(evidence.size(), CV_32S, cv::Scalar(-1));
  for (std::size_t i = 0; i < region.size(); ++i) {
    part_labels.at<int>(region[i].y(), region[i].x()) = assignment[i];
  }
  for (int part = 0; part < parts; ++part) {
    ObjectPart piece;
    for (std::size_t i = 0; i < region.size(); ++i) {
      const Eigen::Vector2i& cell = region[i];
      if (assignment[i] == part && evidence.at<std::uint8_t>(cell.y(), cell.x())) {
        piece.cells.push_back(cell);
      }
    }
    for (std::size_t j = 0; j < observations.size(); ++j) {
      const DetectionObservation& observation = observations[j];
      if (observation.class_id == c && IsOn(observation, part_labels, part, o.detection_overlap)) {
        piece.frames.insert(observation.frame);
        piece.members.push_back(j);
      }
    }
    if (!piece.cells.empty()) pieces->push_back(std::move(piece));
  }
}

// The parts of class c's regions large enough and seen often enough, split where frames saw
// several objects on one region.
std::vector<ObjectPart> ClassPieces(const SemanticGrid& grid, int c, double threshold,
                                    const std::vector<DetectionObservation>& observations,
                                    const ObjectExtractionOptions& o) {
  std::vector<const DetectionObservation*> of_class;
  for (const DetectionObservation& observation : observations) {
    if (observation.class_id == c) of_class.push_back(&observation);
  }
  const ClassRegions regions = FindClassRegions(grid, c, threshold, of_class, o);
  std::vector<ObjectPart> pieces;
  for (int label = 1; label < regions.count; ++label) {
    std::vector<Eigen::Vector2i> region = CellsWithLabel(regions.labels, label);
    if (static_cast<int>(region.size()) < o.min_cells) continue;
    const DetectionsByFrame by_frame = DetectionsOnRegion(of_class, regions.labels, label, o);
    if (static_cast<int>(by_frame.size()) < o.min_observations) continue;
    int parts = 1;
    const std::vector<int> assignment = SplitAmongObjects(region, by_frame, o, &parts);
    AddRegionPieces(region, assignment, parts, regions.evidence, observations, c, o, &pieces);
  }
  return pieces;
}

// The object of a fitted part of class c: its confidence is the mean probability of its cells.
SemanticObject ObjectOf(const FittedPart& fitted, const SemanticGrid& grid, int c,
                        const std::string& class_name, int id) {
  double probability_sum = 0.0;
  for (const Eigen::Vector2i& cell : fitted.part.cells) {
    probability_sum += grid.Probability(c, cell);
  }
  SemanticObject object;
  object.id = id;
  object.class_name = class_name;
  object.center = fitted.shape.center;
  object.footprint = fitted.shape.footprint;
  object.observations = static_cast<int>(fitted.part.frames.size());
  object.confidence = probability_sum / static_cast<double>(fitted.part.cells.size());
  return object;
}

}  // namespace

ExtractedObjects ExtractObjects(const SemanticGrid& grid,
                                const std::vector<DetectionObservation>& observations,
                                const std::vector<std::string>& classes,
                                const SemanticMapOptions& options, const LaserMapCells& laser_map) {
  const ObjectExtractionOptions& o = options.extraction;
  const double threshold = LogitOf(o.occupied_probability);
  ExtractedObjects result;
  result.observation_object.assign(observations.size(), -1);
  std::vector<ClassedPart> classed;
  for (int c = 0; c < grid.class_count(); ++c) {
    const ClassShapePrior prior = options.PriorOf(classes[c]);
    std::vector<ObjectPart> parts = MergeFragments(ClassPieces(grid, c, threshold, observations, o),
                                                   prior, grid.geometry().resolution, o);
    // Specks: too small or too rarely seen to be objects (nor to move one by joining it).
    std::erase_if(parts, [&o](const ObjectPart& part) {
      return static_cast<int>(part.cells.size()) < o.min_cells ||
             static_cast<int>(part.frames.size()) < o.min_observations;
    });
    const auto fit = [&](const ObjectPart& part) {
      return FitPart(grid, c, part, prior,
                     o.faces_on_walls ? laser_map : LaserMapCells{laser_map.free, cv::Mat()});
    };
    // A shape far larger than an object of the class was fitted to evidence that no one object
    // left.
    const double max_extent = o.max_extent_factor * prior.Extent();
    for (FittedPart& fitted : AssociateParts(std::move(parts), fit, prior, o)) {
      if (ShapeExtent(fitted.shape) <= max_extent) classed.push_back({c, std::move(fitted)});
    }
  }
  for (std::size_t k : ResolveClassConflicts(classed, o)) {
    const auto& [c, fitted] = classed[k];
    SemanticObject object =
        ObjectOf(fitted, grid, c, classes[c], static_cast<int>(result.objects.size()));
    for (std::size_t j : fitted.part.members) result.observation_object[j] = object.id;
    result.objects.push_back(std::move(object));
  }
  return result;
}

}  // namespace semchain::semantic
