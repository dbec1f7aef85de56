// One object, one entry: the observations of one object seen with noisy boxes, noisy depth and
// a pose that drifts between passes become one object; neighbouring objects of one class stay
// two. The evidence is made as the pipeline makes it: the surface a camera sees of the object,
// cut to the core of a jittered box, its depth jittered along the ray, and the free space in
// front of it.
#include "semantic/object_association.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <sstream>

#include "semantic/object_extraction.h"

// Named apart from the other tests of the module, which share a unity build with these.
namespace semchain::semantic::association_test {
namespace {

const GridGeometry kGeometry{100, 100, 0.05, Eigen::Vector2d(0.0, 0.0)};
const std::vector<std::string> kClasses = {"chair", "stool"};
constexpr int kChair = 0;
constexpr int kStool = 1;

// An object on the floor plane: a circle or a box (width along x before 'yaw').
struct Shape {
  Eigen::Vector2d center;
  double radius = 0.0;  // > 0: a circle
  double width = 0.0;
  double depth = 0.0;
  double yaw = 0.0;
};

Shape Circle(double x, double y, double radius) { return {{x, y}, radius, 0.0, 0.0, 0.0}; }
Shape Box(double x, double y, double width, double depth) { return {{x, y}, 0.0, width, depth}; }

// Where the ray from 'from' along unit 'direction' first meets 'shape' (metres), or none.
std::optional<double> Intersect(const Shape& shape, const Eigen::Vector2d& from,
                                const Eigen::Vector2d& direction) {
  if (shape.radius > 0.0) {
    const Eigen::Vector2d d = from - shape.center;
    const double b = d.dot(direction);
    const double disc = b * b - (d.squaredNorm() - shape.radius * shape.radius);
    if (disc < 0.0 || -b - std::sqrt(disc) <= 0.0) return std::nullopt;
    return -b - std::sqrt(disc);
  }
  // Slabs in the box's frame.
  const Eigen::Vector2d u(std::cos(shape.yaw), std::sin(shape.yaw));
  const Eigen::Vector2d v(-u.y(), u.x());
  const Eigen::Vector2d o(u.dot(from - shape.center), v.dot(from - shape.center));
  const Eigen::Vector2d d(u.dot(direction), v.dot(direction));
  const Eigen::Vector2d half(0.5 * shape.width, 0.5 * shape.depth);
  double enter = -1e9;
  double leave = 1e9;
  for (int i = 0; i < 2; ++i) {
    if (std::abs(d[i]) < 1e-12) {
      if (std::abs(o[i]) > half[i]) return std::nullopt;
      continue;
    }
    const double t0 = (-half[i] - o[i]) / d[i];
    const double t1 = (half[i] - o[i]) / d[i];
    enter = std::max(enter, std::min(t0, t1));
    leave = std::min(leave, std::max(t0, t1));
  }
  if (enter > leave || enter <= 0.0) return std::nullopt;
  return enter;
}

// Noise of one simulated detector and depth camera.
struct Noise {
  double box_edge = 0.05;  // std of each box edge, as a fraction of the box's width
  double depth = 0.01;     // metres, along the ray
};

// A room of kGeometry's size with objects in it, seen by a forward camera (60° field of view,
// one column per 0.2°) on a robot whose trajectory may be off by a drift.
class NoisyScene {
 public:
  NoisyScene(std::vector<std::pair<int, Shape>> objects, std::uint32_t seed)
      : objects_(std::move(objects)), rng_(seed) {}

  // One frame from a camera at 'viewer' (where the trajectory puts it) looking at 'target',
  // while the world is 'drift' away from where the trajectory puts it. Each object whose
  // columns are all in view is one detection (class, box with jittered edges); the core of the
  // box (10 % trimmed off each side, DetectionPointOptions) gives its points; every column
  // gives free space up to 0.15 m before its surface (FreeSpaceOptions), and its surface counts
  // against the classes whose boxes miss the column (SemanticGridOptions::undetected_log_odds).
  void Frame(const Eigen::Vector2d& viewer, const Eigen::Vector2d& target,
             const Eigen::Vector2d& drift = Eigen::Vector2d::Zero(), const Noise& noise = {}) {
    constexpr double kHalfFov = M_PI / 6.0;
    constexpr int kColumns = 300;
    const double heading = std::atan2(target.y() - viewer.y(), target.x() - viewer.x());
    // The true camera, in the world: the trajectory's viewer less the drift.
    const Eigen::Vector2d camera = viewer - drift;
    const double room = kGeometry.width * kGeometry.resolution;
    struct Column {
      Eigen::Vector2d direction;
      double range = 0.0;
      int object = -1;
    };
    std::vector<Column> columns(kColumns);
    for (int i = 0; i < kColumns; ++i) {
      const double a = heading + kHalfFov - 2.0 * kHalfFov * (i + 0.5) / kColumns;
      Column& column = columns[static_cast<std::size_t>(i)];
      column.direction = Eigen::Vector2d(std::cos(a), std::sin(a));
      column.range = 1e9;  // the room's walls
      for (int axis = 0; axis < 2; ++axis) {
        if (std::abs(column.direction[axis]) < 1e-12) continue;
        const double wall = column.direction[axis] > 0.0 ? room : 0.0;
        column.range = std::min(column.range, (wall - camera[axis]) / column.direction[axis]);
      }
      for (std::size_t o = 0; o < objects_.size(); ++o) {
        const std::optional<double> t = Intersect(objects_[o].second, camera, column.direction);
        if (t && *t < column.range) {
          column.range = *t;
          column.object = static_cast<int>(o);
        }
      }
    }
    std::normal_distribution<double> range_noise(0.0, noise.depth);
    FrameEvidence evidence;
    evidence.hits.resize(kClasses.size());
    evidence.undetected.resize(kClasses.size());
    evidence.viewer = viewer;
    std::vector<std::pair<int, int>> boxes(objects_.size(), {kColumns, -1});  // per object
    for (int i = 0; i < kColumns; ++i) {
      const int o = columns[static_cast<std::size_t>(i)].object;
      if (o < 0) continue;
      boxes[static_cast<std::size_t>(o)].first = std::min(boxes[o].first, i);
      boxes[static_cast<std::size_t>(o)].second = std::max(boxes[o].second, i);
    }
    std::vector<std::vector<bool>> boxed(kClasses.size(), std::vector<bool>(kColumns, false));
    for (std::size_t o = 0; o < objects_.size(); ++o) {
      auto [first, last] = boxes[o];
      if (last < 0 || first == 0 || last == kColumns - 1) continue;  // not in view, or cut off
      const int class_id = objects_[o].first;
      std::normal_distribution<double> edge(0.0, noise.box_edge * (last - first + 1));
      const double left = first + edge(rng_);
      const double right = last + 1 + edge(rng_);
      const double trim = 0.1 * (right - left);
      std::map<std::pair<int, int>, std::pair<Eigen::Vector2d, int>> cells;
      for (int i = 0; i < kColumns; ++i) {
        const double center = i + 0.5;
        if (center < left || center > right) continue;
        boxed[static_cast<std::size_t>(class_id)][static_cast<std::size_t>(i)] = true;
        const Column& column = columns[static_cast<std::size_t>(i)];
        if (center < left + trim || center > right - trim || column.object < 0 ||
            objects_[static_cast<std::size_t>(column.object)].first != class_id) {
          continue;
        }
        // Seen from the trajectory's camera: the point moves with the drift.
        const Eigen::Vector2d seen = viewer + (column.range + range_noise(rng_)) * column.direction;
        const Eigen::Vector2i cell = kGeometry.CellOf(seen);
        auto& [sum, count] = cells[{cell.x(), cell.y()}];
        if (count == 0) sum = Eigen::Vector2d::Zero();
        sum += seen;
        ++count;
      }
      DetectionObservation observation{frames_, class_id, 0.9, {}};
      for (const auto& [key, value] : cells) {
        const Eigen::Vector2i cell(key.first, key.second);
        evidence.hits[static_cast<std::size_t>(class_id)].push_back(
            {cell, value.first / value.second});
        observation.cells.push_back(cell);
      }
      if (!observation.cells.empty()) observations.push_back(std::move(observation));
    }
    std::set<std::pair<int, int>> free;
    std::vector<std::set<std::pair<int, int>>> undetected(kClasses.size());
    for (int i = 0; i < kColumns; ++i) {
      const Column& column = columns[static_cast<std::size_t>(i)];
      for (double s = 0.0; s < column.range - 0.15; s += 0.025) {
        const Eigen::Vector2i cell = kGeometry.CellOf(viewer + s * column.direction);
        free.insert({cell.x(), cell.y()});
      }
      const Eigen::Vector2i surface = kGeometry.CellOf(viewer + column.range * column.direction);
      for (std::size_t c = 0; c < kClasses.size(); ++c) {
        if (!boxed[c][static_cast<std::size_t>(i)])
          undetected[c].insert({surface.x(), surface.y()});
      }
    }
    for (const auto& [x, y] : free) evidence.free_cells.emplace_back(x, y);
    for (std::size_t c = 0; c < kClasses.size(); ++c) {
      for (const auto& [x, y] : undetected[c]) evidence.undetected[c].emplace_back(x, y);
    }
    grid.Update(evidence);
    ++frames_;
  }

  // From the next frame on, the detector names object 'index' 'class_id'.
  void Rename(std::size_t index, int class_id) { objects_[index].first = class_id; }

  ExtractedObjects Extract(const SemanticMapOptions& options = {}) const {
    return ExtractObjects(grid, observations, kClasses, options);
  }

  SemanticGrid grid{kGeometry, static_cast<int>(kClasses.size()), SemanticGridOptions()};
  std::vector<DetectionObservation> observations;

 private:
  std::vector<std::pair<int, Shape>> objects_;
  std::mt19937 rng_;
  int frames_ = 0;
};

// The objects of class 'name'.
std::vector<SemanticObject> OfClass(const ExtractedObjects& result, const std::string& name) {
  std::vector<SemanticObject> objects;
  for (const SemanticObject& object : result.objects) {
    if (object.class_name == name) objects.push_back(object);
  }
  return objects;
}

// The objects of 'objects', for failure messages.
std::string Describe(const std::vector<SemanticObject>& objects) {
  std::ostringstream text;
  for (const SemanticObject& object : objects) {
    text << " " << object.class_name << " (" << object.center.x() << ", " << object.center.y()
         << ") seen " << object.observations << "x;";
  }
  return text.str();
}

// A fitted box of 'width' × 'depth' (axis-aligned) or, with depth 0, a 16-gon circle of radius
// 'width', centred at (x, y).
FittedShape Fitted(double x, double y, double width, double depth = 0.0) {
  FittedShape shape;
  shape.center = Eigen::Vector2d(x, y);
  if (depth == 0.0) {
    shape.radius = width;
    for (int i = 0; i < 16; ++i) {
      const double a = 2.0 * M_PI * i / 16;
      shape.footprint.push_back(shape.center + width * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
    return shape;
  }
  shape.width = width;
  shape.depth = depth;
  const Eigen::Vector2d h(0.5 * width, 0.5 * depth);
  shape.footprint = {shape.center - h, shape.center + Eigen::Vector2d(h.x(), -h.y()),
                     shape.center + h, shape.center + Eigen::Vector2d(-h.x(), h.y())};
  return shape;
}

TEST(ObjectAssociationTest, OverlapAreaOfTwoBoxes) {
  // 0.6 × 0.4 boxes 0.4 m apart along their width share 0.2 × 0.4; far from the map origin too.
  EXPECT_NEAR(
      OverlapArea(Fitted(1.0, 1.0, 0.6, 0.4).footprint, Fitted(1.4, 1.0, 0.6, 0.4).footprint), 0.08,
      1e-6);
  EXPECT_NEAR(OverlapArea(Fitted(901.0, 501.0, 0.6, 0.4).footprint,
                          Fitted(901.4, 501.0, 0.6, 0.4).footprint),
              0.08, 1e-5);
  EXPECT_EQ(OverlapArea(Fitted(1.0, 1.0, 0.6, 0.4).footprint, Fitted(1.7, 1.0, 0.6, 0.4).footprint),
            0.0);
}

TEST(ObjectAssociationTest, SeenAsTwoNeedsEnoughFramesAndEnoughOfThem) {
  const ObjectExtractionOptions options;  // 3 frames, and a tenth of the frames
  EXPECT_FALSE(SeenAsTwo(2, 4, options));
  EXPECT_TRUE(SeenAsTwo(3, 4, options));
  EXPECT_TRUE(SeenAsTwo(3, 30, options));
  EXPECT_FALSE(SeenAsTwo(3, 31, options));
  EXPECT_TRUE(SeenAsTwo(7, 61, options));
  EXPECT_FALSE(SeenAsTwo(4, 61, options));
  ObjectPart a, b;
  for (int f = 1; f <= 17; ++f) a.frames.insert(f);
  for (int f = 15; f <= 30; ++f) b.frames.insert(f);
  EXPECT_TRUE(PartsSeenAsTwo(a, b, options));  // 3 together of 30 frames
  b.frames.insert(31);
  EXPECT_FALSE(PartsSeenAsTwo(a, b, options));  // 3 of 31
}

TEST(ObjectAssociationTest, SameObjectByOverlapOrCentreUnlessSeenTogether) {
  const ObjectExtractionOptions options;
  ClassShapePrior cabinet;  // 0.6 × 0.4: half diagonal 0.36 m
  cabinet.width = 0.6;
  cabinet.depth = 0.4;
  // 0.4 m apart along the width: beyond the half diagonal, but a third of each overlaps.
  EXPECT_TRUE(
      SameObject(Fitted(1.0, 1.0, 0.6, 0.4), Fitted(1.4, 1.0, 0.6, 0.4), false, cabinet, options));
  // The same, seen as two detections at once: two cabinets.
  EXPECT_FALSE(
      SameObject(Fitted(1.0, 1.0, 0.6, 0.4), Fitted(1.4, 1.0, 0.6, 0.4), true, cabinet, options));
  // Side by side, 0.62 m apart: two.
  EXPECT_FALSE(
      SameObject(Fitted(1.0, 1.0, 0.6, 0.4), Fitted(1.62, 1.0, 0.6, 0.4), false, cabinet, options));
  // 0.4 m apart front to back: the footprints only touch, and the centres are beyond the
  // half diagonal: two.
  EXPECT_FALSE(
      SameObject(Fitted(1.0, 1.0, 0.6, 0.4), Fitted(1.0, 1.4, 0.6, 0.4), false, cabinet, options));
  ClassShapePrior stool;  // radius 0.17: half diagonal 0.24 m
  stool.shape = ClassShapePrior::Shape::kCircle;
  stool.radius = 0.17;
  // 0.22 m apart: within the half diagonal.
  EXPECT_TRUE(SameObject(Fitted(1.0, 1.0, 0.17), Fitted(1.22, 1.0, 0.17), false, stool, options));
  // 0.36 m apart: apart.
  EXPECT_FALSE(SameObject(Fitted(1.0, 1.0, 0.17), Fitted(1.36, 1.0, 0.17), false, stool, options));
}

// Frames from viewers on an arc of 'distance' around 'target', from 'from' to 'to' radians.
void SeeFromArc(NoisyScene& scene, const Eigen::Vector2d& target, double distance, double from,
                double to, int frames, const Eigen::Vector2d& drift = Eigen::Vector2d::Zero()) {
  for (int i = 0; i < frames; ++i) {
    const double a = from + (to - from) * i / std::max(1, frames - 1);
    scene.Frame(target + distance * Eigen::Vector2d(std::cos(a), std::sin(a)), target, drift);
  }
}

// Each noisy case is drawn with seeds 1..kSeeds.
constexpr std::uint32_t kSeeds = 10;

// The trajectory's error on the way back (a small loop-closure residual).
const Eigen::Vector2d kDrift(0.16, 0.12);

TEST(ObjectAssociationTest, StoolSeenFromTwoSidesWithDriftIsOneObject) {
  // A stool seen on the way out from the south and on the way back from the north, the
  // trajectory 0.2 m off between the passes: the two arcs are the stool's two sides, a
  // diameter apart; the rays that pass beside it clear the cells between them.
  const Shape stool = Circle(2.5, 2.5, 0.17);
  for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
    NoisyScene scene({{kStool, stool}}, seed);
    SeeFromArc(scene, stool.center, 1.3, -1.8, -1.35, 6);
    SeeFromArc(scene, stool.center, 1.3, 1.35, 1.8, 6, kDrift);
    const std::vector<SemanticObject> stools = OfClass(scene.Extract(), "stool");
    if (stools.size() != 1u) {
      ADD_FAILURE() << "seed " << seed << ": " << stools.size() << " objects:" << Describe(stools);
      continue;
    }
    // Between where the two passes put it.
    EXPECT_LT((stools[0].center - (stool.center + 0.5 * kDrift)).norm(), 0.08) << "seed " << seed;
    EXPECT_EQ(stools[0].observations, 12) << "seed " << seed;
  }
}

TEST(ObjectAssociationTest, TwoChairsSideBySideSeenOneAtATimeStayTwo) {
  // Two chairs 0.6 m apart (a 0.1 m gap between them), each seen on its own from close by on
  // its outer side, so that no frame shows both whole: only their shapes tell that they are two.
  const Shape left = Box(2.2, 2.5, 0.5, 0.5);
  const Shape right = Box(2.8, 2.5, 0.5, 0.5);
  for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
    NoisyScene scene({{kChair, left}, {kChair, right}}, seed);
    SeeFromArc(scene, left.center, 0.9, -2.3, -1.8, 5);
    SeeFromArc(scene, right.center, 0.9, -1.35, -0.85, 5);
    const std::vector<SemanticObject> chairs = OfClass(scene.Extract(), "chair");
    if (chairs.size() != 2u) {
      ADD_FAILURE() << "seed " << seed << ": " << chairs.size() << " objects:" << Describe(chairs);
      continue;
    }
    const double x0 = std::min(chairs[0].center.x(), chairs[1].center.x());
    const double x1 = std::max(chairs[0].center.x(), chairs[1].center.x());
    EXPECT_NEAR(x0, 2.2, 0.08) << "seed " << seed;
    EXPECT_NEAR(x1, 2.8, 0.08) << "seed " << seed;
  }
}

TEST(ObjectAssociationTest, TwoChairsSeenTogetherStayTwo) {
  // The same chairs at a table, seen together from farther back.
  const Shape left = Box(2.2, 2.5, 0.5, 0.5);
  const Shape right = Box(2.8, 2.5, 0.5, 0.5);
  NoisyScene scene({{kChair, left}, {kChair, right}}, 7);
  SeeFromArc(scene, {2.5, 2.5}, 1.8, -1.9, -1.2, 6);
  EXPECT_EQ(OfClass(scene.Extract(), "chair").size(), 2u);
}

TEST(ObjectAssociationTest, TwoStoolsSeenFromBothSidesStayTwo) {
  // Two stools 0.45 m apart (an 0.11 m gap), each seen on its own from the south and from the
  // north, 0.1 m off on the way back: four arcs, each stool's two a diameter apart and the
  // nearest two of different stools 0.2 m apart.
  const Shape a = Circle(2.3, 2.5, 0.17);
  const Shape b = Circle(2.75, 2.5, 0.17);
  const Eigen::Vector2d drift = 0.5 * kDrift;
  for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
    NoisyScene scene({{kStool, a}, {kStool, b}}, seed);
    SeeFromArc(scene, a.center, 0.8, -2.2, -1.8, 6);
    SeeFromArc(scene, b.center, 0.8, -1.35, -0.95, 6);
    SeeFromArc(scene, a.center, 0.8, 1.8, 2.2, 6, drift);
    SeeFromArc(scene, b.center, 0.8, 0.95, 1.35, 6, drift);
    std::vector<SemanticObject> stools = OfClass(scene.Extract(), "stool");
    if (stools.size() != 2u) {
      ADD_FAILURE() << "seed " << seed << ": " << stools.size() << " objects:" << Describe(stools);
      continue;
    }
    if (stools[0].center.x() > stools[1].center.x()) std::swap(stools[0], stools[1]);
    EXPECT_LT((stools[0].center - (a.center + 0.5 * drift)).norm(), 0.08) << "seed " << seed;
    EXPECT_LT((stools[1].center - (b.center + 0.5 * drift)).norm(), 0.08) << "seed " << seed;
    // Each from both passes.
    EXPECT_GE(stools[0].observations, 9) << "seed " << seed;
    EXPECT_GE(stools[1].observations, 9) << "seed " << seed;
  }
}

// A part of 'class_id' with 'shape', detected in frames first .. last.
ClassedPart PartOf(int class_id, const FittedShape& shape, int first, int last) {
  ClassedPart part{class_id, {}};
  part.fitted.shape = shape;
  for (int f = first; f <= last; ++f) part.fitted.part.frames.insert(f);
  part.fitted.part.cells.assign(static_cast<std::size_t>(last - first + 1), Eigen::Vector2i(0, 0));
  return part;
}

TEST(ObjectAssociationTest, OneObjectTwoNamesByOverlapUnlessSeenTogether) {
  const ObjectExtractionOptions options;  // half of the smaller footprint
  // A 0.5 m chair's fit and a stool's fit 0.1 m off it, never in the same frame: one object.
  const ClassedPart chair = PartOf(kChair, Fitted(1.0, 1.0, 0.5, 0.5), 0, 9);
  EXPECT_TRUE(OneObjectTwoNames(chair, PartOf(kStool, Fitted(1.1, 1.0, 0.17), 10, 14), options));
  // The same with both in three of the fifteen frames: the detector saw two objects there (a
  // computer on a desk).
  EXPECT_FALSE(OneObjectTwoNames(chair, PartOf(kStool, Fitted(1.1, 1.0, 0.17), 7, 14), options));
  // A stool at the chair's side, a third of it under the chair's fit: two.
  EXPECT_FALSE(OneObjectTwoNames(chair, PartOf(kStool, Fitted(1.35, 1.0, 0.17), 10, 14), options));
  // One class: AssociateParts' concern, not this.
  EXPECT_FALSE(
      OneObjectTwoNames(chair, PartOf(kChair, Fitted(1.1, 1.0, 0.5, 0.5), 10, 14), options));
  ObjectExtractionOptions off;
  off.merge_across_classes = 2.0;
  EXPECT_FALSE(OneObjectTwoNames(chair, PartOf(kStool, Fitted(1.1, 1.0, 0.17), 10, 14), off));
}

TEST(ObjectAssociationTest, TheNameSeenInMoreFramesIsKept) {
  const ObjectExtractionOptions options;
  const std::vector<ClassedPart> parts = {
      PartOf(kStool, Fitted(1.1, 1.0, 0.17), 10, 14),       // 5 frames
      PartOf(kChair, Fitted(1.0, 1.0, 0.5, 0.5), 0, 9),     // 10 frames: kept
      PartOf(kStool, Fitted(3.0, 1.0, 0.17), 20, 22),       // elsewhere: kept
      PartOf(kChair, Fitted(3.05, 1.0, 0.5, 0.5), 23, 24),  // 2 frames against its 3
  };
  EXPECT_EQ(ResolveClassConflicts(parts, options), (std::vector<std::size_t>{1, 2}));
}

TEST(ObjectAssociationTest, APieceTooSmallToBeAStoolNearOneIsThatStool) {
  // Office_floor from pixels: a 0.5 m stool mapped as a 0.31 m stool seen in 31 frames and a
  // 0.13 m piece seen in 5 others, their centres 0.36 m apart (beyond the half diagonal, 0.24 m,
  // and their footprints apart), their cells 0.55 m apart (beyond the fragments' gap).
  ClassShapePrior stool;  // 0.34 m across: a piece under 0.17 m is no stool of its own
  stool.shape = ClassShapePrior::Shape::kCircle;
  stool.radius = 0.17;
  const ObjectExtractionOptions options;
  const FittedPart main = PartOf(kStool, Fitted(1.0, 1.0, 0.155), 0, 30).fitted;
  const FittedPart piece = PartOf(kStool, Fitted(1.0, 0.64, 0.065), 31, 35).fitted;
  EXPECT_FALSE(SameObject(main.shape, piece.shape, false, stool, options));
  const std::vector<FittedPart> joined = AbsorbFragments({main, piece}, stool, options);
  ASSERT_EQ(joined.size(), 1u);
  // The stool keeps its shape and counts the piece's frames.
  EXPECT_EQ(joined[0].shape.center, main.shape.center);
  EXPECT_EQ(joined[0].part.frames.size(), 36u);
  ObjectExtractionOptions off = options;
  off.absorb_fragments = false;
  EXPECT_EQ(AbsorbFragments({main, piece}, stool, off).size(), 2u);
  // Seen in six of its frames together with the stool: a second object (a stool half hidden).
  const FittedPart together = PartOf(kStool, Fitted(1.0, 0.64, 0.065), 25, 35).fitted;
  EXPECT_EQ(AbsorbFragments({main, together}, stool, options).size(), 2u);
  // Beyond the prior's diagonal (0.48 m): a piece of something else.
  const FittedPart far = PartOf(kStool, Fitted(1.0, 0.5, 0.065), 31, 35).fitted;
  EXPECT_EQ(AbsorbFragments({main, far}, stool, options).size(), 2u);
  // Two whole stools 0.45 m apart stay two: neither is a piece.
  const FittedPart other = PartOf(kStool, Fitted(1.45, 1.0, 0.16), 31, 35).fitted;
  EXPECT_EQ(AbsorbFragments({main, other}, stool, options).size(), 2u);
  // A piece between two stools joins the nearer one.
  const FittedPart between = PartOf(kStool, Fitted(1.3, 1.0, 0.065), 40, 42).fitted;
  const std::vector<FittedPart> three = AbsorbFragments({main, other, between}, stool, options);
  ASSERT_EQ(three.size(), 2u);
  EXPECT_EQ(three[0].part.frames.size(), 31u);
  EXPECT_EQ(three[1].part.frames.size(), 8u);
}

TEST(ObjectAssociationTest, ChairNamedStoolFromOneSideIsOneChair) {
  // A chair that the detector names a chair from the south (8 frames) and a stool from the
  // north (5 frames): one object, a chair. Without the rule: a chair and a stool on one spot.
  const Shape chair = Box(2.5, 2.5, 0.5, 0.5);
  SemanticMapOptions per_class;
  per_class.extraction.merge_across_classes = 2.0;
  for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
    NoisyScene scene({{kChair, chair}}, seed);
    SeeFromArc(scene, chair.center, 1.3, -1.9, -1.25, 8);
    scene.Rename(0, kStool);
    SeeFromArc(scene, chair.center, 1.3, 1.35, 1.8, 5, 0.5 * kDrift);
    const ExtractedObjects objects = scene.Extract();
    if (objects.objects.size() != 1u) {
      ADD_FAILURE() << "seed " << seed << ": " << objects.objects.size()
                    << " objects:" << Describe(objects.objects);
      continue;
    }
    EXPECT_EQ(objects.objects[0].class_name, "chair") << "seed " << seed;
    EXPECT_LT((objects.objects[0].center - chair.center).norm(), 0.12) << "seed " << seed;
    EXPECT_EQ(scene.Extract(per_class).objects.size(), 2u) << "seed " << seed;
  }
}

TEST(ObjectAssociationTest, EvidenceAlongMetresOfWallIsNoObject) {
  // A detector that names a 4 m long, low cupboard front a chair in every frame (seen whole
  // from 4 m away): the chair layer fills along 4 m, eight times a chair's size; no chair is
  // mapped there. A 1 m bench (twice a chair's size) named a chair stays an object.
  SemanticMapOptions unbounded;
  unbounded.extraction.max_extent_factor = 100.0;
  NoisyScene wall({{kChair, Box(2.5, 4.5, 4.0, 0.3)}}, 3);
  for (int i = 0; i < 8; ++i) wall.Frame({2.15 + 0.1 * i, 0.3}, {2.15 + 0.1 * i, 4.5});
  EXPECT_EQ(wall.Extract().objects.size(), 0u) << Describe(wall.Extract().objects);
  EXPECT_EQ(wall.Extract(unbounded).objects.size(), 1u);
  NoisyScene bench({{kChair, Box(2.5, 3.5, 1.0, 0.4)}}, 3);
  for (int i = 0; i < 8; ++i) bench.Frame({2.0 + 0.15 * i, 1.5}, {2.5, 3.5});
  EXPECT_EQ(bench.Extract().objects.size(), 1u) << Describe(bench.Extract().objects);
}

}  // namespace
}  // namespace semchain::semantic::association_test
