#pragma once

#include <Eigen/Core>
#include <functional>
#include <set>
#include <vector>

#include "semantic/semantic_options.h"
#include "semantic/shape_fit.h"

// One object, one entry (DESIGN.md §3.4): the parts of a class layer that are pieces or views
// of one object are joined before they become objects. Noise splits one object into several
// parts: a face cut off by the image edge, the two sides of an object seen on two passes of a
// trajectory that drifted in between, the cells between them cleared by rays passing beside
// it. Two neighbours of one class are kept apart by what only two objects give: two detections
// in the same frames, or two fitted shapes that neither overlap nor stand closer than an
// object of the class is large.
namespace semchain::semantic {

// One object's share of a class layer: its cells with evidence and the detections on them.
struct ObjectPart {
  std::vector<Eigen::Vector2i> cells;
  std::set<int> frames;
  std::vector<std::size_t> members;  // indices of the observations
};

// How many frames saw both parts (a detection on each).
int FramesTogether(const ObjectPart& a, const ObjectPart& b);

// Whether 'together' frames with two detections at once, of 'seen' frames with a detection on
// the place, show two objects there (ObjectExtractionOptions::min_split_frames, min_split_share).
bool SeenAsTwo(int together, int seen, const ObjectExtractionOptions& options);

// SeenAsTwo of two parts: the frames that saw both, of the frames that saw either.
bool PartsSeenAsTwo(const ObjectPart& a, const ObjectPart& b,
                    const ObjectExtractionOptions& options);

// The largest extent of the part's cells (metres; cells of 'resolution' metres).
double PartExtent(const ObjectPart& part, double resolution);

// Joins fragments (ObjectExtractionOptions::merge_gap_cells, fragment_fraction): cell-based,
// before any shape is fitted, so that a piece too small to be an object joins the object it
// was cut from.
std::vector<ObjectPart> MergeFragments(std::vector<ObjectPart> parts, const ClassShapePrior& prior,
                                       double resolution, const ObjectExtractionOptions& options);

// The area of the intersection of two convex polygons (square metres).
double OverlapArea(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b);

// Whether two fitted parts of one class are one object (ObjectExtractionOptions::
// merge_overlap, merge_center_fraction); 'seen_as_two' is PartsSeenAsTwo of the parts.
bool SameObject(const FittedShape& a, const FittedShape& b, bool seen_as_two,
                const ClassShapePrior& prior, const ObjectExtractionOptions& options);

// A part with its fitted shape.
struct FittedPart {
  ObjectPart part;
  FittedShape shape;
};

// Joins the parts that SameObject says are one object, closest centres first, refitting each
// joined part with 'fit' before it is compared again; then AbsorbFragments.
std::vector<FittedPart> AssociateParts(std::vector<ObjectPart> parts,
                                       const std::function<FittedShape(const ObjectPart&)>& fit,
                                       const ClassShapePrior& prior,
                                       const ObjectExtractionOptions& options);

// A piece too small to be an object of the class (its fitted shape spans less than
// ObjectExtractionOptions::fragment_fraction of the prior's extent) whose centre lies within
// the prior's diagonal of a larger part's, not seen as two with it, is a piece of that object
// seen apart: the two centres of pieces of one object are at most its diagonal apart, farther
// than SameObject's half diagonal. Its detections join the nearest such part (they count as
// that object's observations) but not its cells, so that the object's fit keeps its shape (a
// wrong "table" piece 0.9 m from a desk, joined cell by cell, pulled the desk's centre 0.4 m).
// Office_floor from pixels mapped a 0.5 m stool as a 0.31 m stool and a 0.13 m piece 0.36 m
// apart, their cells 0.55 m apart.
std::vector<FittedPart> AbsorbFragments(std::vector<FittedPart> fitted,
                                        const ClassShapePrior& prior,
                                        const ObjectExtractionOptions& options);

// A fitted part of class 'class_id'.
struct ClassedPart {
  int class_id = 0;
  FittedPart fitted;
};

// Whether two fitted parts of different classes are one object that the detector named two
// ways (ObjectExtractionOptions::merge_across_classes): their footprints overlap by at least
// that fraction of the smaller, and frames did not show both (SeenAsTwo). An object stands on
// another (a computer on a desk) or beside it (a stool at a table) in view of both, so the
// detector reports the two in the same frames; one object named a bed from one side and a sofa
// from another is reported once a frame, now by one class, now by the other.
bool OneObjectTwoNames(const ClassedPart& a, const ClassedPart& b,
                       const ObjectExtractionOptions& options);

// Keeps one entry of each object named two ways (OneObjectTwoNames): of such a pair the name
// seen in more frames (more cells on a tie) wins and the other part is dropped, pairs of
// largest overlap first. Returns the indices of 'parts' kept, in order.
std::vector<std::size_t> ResolveClassConflicts(const std::vector<ClassedPart>& parts,
                                               const ObjectExtractionOptions& options);

}  // namespace semchain::semantic
