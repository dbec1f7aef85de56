#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

// The settings of semantic mapping (DESIGN.md §3.4–3.5), with the defaults used by
// `semchain semantic`, `slam --semantic` and the node; they are set here, not read from a file.
namespace semchain::semantic {

// The footprint a class of object usually has; it completes objects seen from one side only
// (a cabinet against a wall shows only its front) so that the centre is the object's.
struct ClassShapePrior {
  enum class Shape { kBox, kCircle };
  Shape shape = Shape::kBox;
  double width = 0.5;   // box: along its face, metres
  double depth = 0.5;   // box: front to back, metres
  double radius = 0.2;  // circle, metres
  // How strongly the prior holds the fitted size when the observations say little (metres,
  // standard deviation of the size about the prior).
  double size_std = 0.05;

  // The largest horizontal extent of the shape.
  double Extent() const { return shape == Shape::kBox ? std::max(width, depth) : 2.0 * radius; }
  // Half the diagonal of the footprint's bounding box (of the square about a circle).
  double HalfDiagonal() const {
    return shape == Shape::kBox ? 0.5 * std::hypot(width, depth) : std::sqrt(2.0) * radius;
  }
};

// Priors for the ten classes of seed 000 (door, cabinet, bucket, chair, stool, table, sofa,
// computer, bed, clock), typical sizes of sim/object_shapes.h; others get the ClassShapePrior
// defaults.
std::map<std::string, ClassShapePrior> DefaultClassPriors();

struct SemanticGridOptions {
  // Log-odds added to a class layer where a detection's points fall (P = 0.7) and where the
  // camera saw through the cell or saw another class there (P = 0.4) — seed 001 eq. 2 with the
  // inverse sensor model of occupancy mapping.
  double hit_log_odds = 0.847;
  double miss_log_odds = -0.405;
  // Added where the camera saw a surface but the detector reported nothing of the class (P =
  // 0.45: weak, since a detector misses objects that are partly out of view).
  double undetected_log_odds = -0.2;
  double max_abs_log_odds = 5.0;
};

struct DetectionPointOptions {
  // Points below this height are floor (metres).
  double min_height = 0.05;
  // The box edges are jittered by the detector; its core is used so that a neighbour's pixels
  // at the edge are not taken for the object. Fraction of the width/height cut on each side,
  // at least 'min_trim_px'.
  double box_trim_fraction = 0.1;
  double min_trim_px = 2.0;
  // A pixel belongs to the object when its depth is within this many times the class extent of
  // the detection's depth (the median depth of the visible surface), bounded below and above.
  // The upper bound lets a deep object (a sofa's back 0.7 m behind its seat front, a bed) keep
  // its far surfaces; objects up to 1 m across (all of the first five classes) never reach it.
  double depth_gate_factor = 0.5;
  double min_depth_gate = 0.1;
  double max_depth_gate = 1.0;
  // Every 'pixel_stride'-th pixel in both directions is used.
  int pixel_stride = 1;
  // Detections with a lower score are ignored. Below a detector's confidence at its best F1 on
  // its validation split, lowering the bar costs it more precision than it gains recall. The
  // value is the default model's (stage 11: 0.414 on seed 202's validation split, `semchain
  // bench detector --split val`), rounded down (docs/results.md, "From pixels"); a model of one's
  // own has its own. The detector itself keeps its lower threshold (0.25) for the frames it shows.
  double min_score = 0.40;
};

struct FreeSpaceOptions {
  // Image columns sampled for the free-space rays (every 'column_stride'-th).
  int column_stride = 2;
  // Free space ends this far before the nearest surface seen in a column (metres), so that the
  // surface cells themselves are not lowered by depth noise.
  double surface_margin = 0.15;
  // Pixels between these heights (metres) bound the free space of their column.
  double min_height = 0.05;
  double max_height = 2.0;
};

struct ObjectExtractionOptions {
  // Cells whose class probability exceeds this belong to the class layer (P = 0.8: at least two
  // more hits than misses).
  double occupied_probability = 0.8;
  // Square kernel sizes (cells) of the morphological clean-up (seed 001 §1.1): dilation then
  // erosion (closing) fills the gaps between an object's cells; erosion then dilation (opening)
  // removes specks. Opening is off by default: seen from one side, an object is a line one or
  // two cells thick, which an opening would erase; specks are removed by 'min_cells' and
  // 'min_observations' instead. 0 or 1 disables a step.
  int closing_kernel = 3;
  int opening_kernel = 0;
  // Regions smaller than this (cells) or seen in fewer frames are noise.
  int min_cells = 2;
  int min_observations = 3;
  // A shape fitted larger than this many times the class prior's extent is not one object: a
  // detector that takes a corridor for a bed, frame after frame, paints the bed layer along
  // metres of wall. Real objects of a class differ in size, but by less than three times the
  // typical one (a 1.8 m wardrobe against a 0.6 m cabinet, a double door, a long table).
  double max_extent_factor = 3.0;
  // A region is split into k objects when at least this many frames show k detections of its
  // class on it (two cabinets side by side merge on a 5 cm grid), and at least this share of
  // the frames with a detection on it: a detector's mistakes come at a rate, so a real detector
  // seeing a region in 60 frames gives a few frames with a second, wrong box on it (a chair in
  // front of a desk named a table), while two objects side by side show as two in most frames
  // that see them. 0: the count alone decides.
  int min_split_frames = 3;
  double min_split_share = 0.1;
  // A detection is on a region when this fraction of its cells lies in it.
  double detection_overlap = 0.5;
  // Two regions of a class are one object's faces when at least 'min_bridges' detections each
  // put this fraction of their cells (and at least min_cells) on both.
  double bridge_fraction = 0.2;
  int min_bridges = 2;
  // One object, one entry (object_association.h). Parts of a class that were not seen as two
  // (SeenAsTwo: min_split_frames frames, and min_split_share of the frames that saw either,
  // with a detection on each) are one object when:
  // - they lie within 'merge_gap_cells' of each other and the smaller spans less than
  //   'fragment_fraction' of the class prior's extent: a piece too small to be an object of the
  //   class (a face cut off by the image edge);
  // - their fitted centres are closer than 'merge_center_fraction' times the prior's half
  //   diagonal. Two objects of the class standing side by side have centres at least their
  //   smaller size apart (footprints do not overlap), which is more than the half diagonal for
  //   every class not longer than √3 times its depth (a circle: 2 r > √2 r); the longer ones
  //   (door, sofa, computer, clock) stand side by side along their length. So centres within
  //   the half diagonal are one object seen twice, e.g. its two sides on two passes of a
  //   drifting trajectory, whose fits land a drift apart.
  // - their fitted footprints overlap by at least 'merge_overlap' of the smaller: solid
  //   objects do not overlap, and the fits of two neighbours overlap only by their errors (the
  //   prior's size_std, 0.05 m, on each side of a 0.5 m chair: 0.2 of it); above 1: never.
  // - (absorb_fragments) a piece whose fitted shape spans less than 'fragment_fraction' of the
  //   prior's extent, within the prior's diagonal of a larger part's centre, is a piece of that
  //   object seen apart (AbsorbFragments): its detections count as the object's, its cells do
  //   not reshape it. false: it stays an object of its own.
  int merge_gap_cells = 5;
  double fragment_fraction = 0.5;
  bool absorb_fragments = true;
  double merge_center_fraction = 1.0;
  double merge_overlap = 0.25;
  // One object, one name (OneObjectTwoNames): parts of two classes whose footprints overlap by
  // at least this fraction of the smaller, not seen as two, are one object; the name seen in
  // more frames is kept. A detector names one object differently from different sides (a sofa
  // as big as a bed, a door as a cabinet). Stricter than 'merge_overlap': each part's shape is
  // completed from its own class's prior, so the fits of one object under two names are offset
  // by up to half their difference in size, and those of two neighbours can overlap by as
  // much. Above 1: every class layer keeps its objects.
  double merge_across_classes = 0.5;
  // A face lying on a wall of the laser map is the back of an object standing in front of it
  // (shape_fit.h): a chair's back against the wall, seen from the room, whose fit behind the
  // face put it beyond the wall. false: every face is taken for the object's front.
  bool faces_on_walls = true;
};

struct ChainOptions {
  // Free space is cut into regions (rooms, corridors) at doorways narrower than twice this
  // (metres): the cores of the regions are the cells farther than this from any obstacle.
  double doorway_half_width = 0.6;
  // Gaps in walls up to this many cells (minus one) are closed before the cut.
  int wall_closing_kernel = 7;
  // Cores smaller than this (square metres) are not regions of their own.
  double min_region_area = 0.5;
  // The neighbour graph joins every object to its k nearest mutually visible objects.
  int neighbours = 3;
  // Objects farther apart than this are not neighbours (metres).
  double max_neighbour_distance = 8.0;
};

struct SemanticMapOptions {
  SemanticGridOptions grid;
  DetectionPointOptions points;
  FreeSpaceOptions free_space;
  ObjectExtractionOptions extraction;
  ChainOptions chain;
  std::map<std::string, ClassShapePrior> priors = DefaultClassPriors();
  // A frame's pose is the trajectory pose at its stamp: the nearest within this tolerance
  // (seconds), otherwise interpolated across gaps of at most 'max_pose_gap'.
  double pose_tolerance = 0.02;
  double max_pose_gap = 1.0;

  // The prior of 'class_name' (the ClassShapePrior defaults for unknown classes).
  ClassShapePrior PriorOf(const std::string& class_name) const;
  bool Validate(std::string* error) const;
};

}  // namespace semchain::semantic
