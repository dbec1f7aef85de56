#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "semantic/semantic_grid.h"
#include "semantic/semantic_map.h"
#include "semantic/semantic_options.h"

// Objects from the semantic grid (DESIGN.md §3.4): each class layer is thresholded, cleaned by
// dilation and erosion (seed 001 §1.1), and cut into connected regions; a region on which
// several detections of its class fall in the same frames is split into that many objects
// (side-by-side cabinets touch on a 5 cm grid); each object's shape is completed from its
// class prior (shape_fit.h), parts that are one object are joined, shapes far larger than
// their class are dropped, and an object named two ways keeps one name (object_association.h).
namespace semchain::semantic {

// One detection's footprint on the map.
struct DetectionObservation {
  int frame = 0;  // index of the frame in the run
  int class_id = 0;
  double score = 0.0;
  std::vector<Eigen::Vector2i> cells;  // each once
};

struct ExtractedObjects {
  std::vector<SemanticObject> objects;  // ids 0, 1, ... in extraction order
  // For each observation, the id of the object it fell on, or -1.
  std::vector<int> observation_object;
};

// What the laser map says about the grid's cells: CV_8UC1 masks of the grid's size, non-zero
// where the laser map is free, or occupied (empty: not known). The shapes fitted to the objects
// keep off free space and stand in front of walls (shape_fit.h).
struct LaserMapCells {
  cv::Mat free;
  cv::Mat occupied;
};

ExtractedObjects ExtractObjects(const SemanticGrid& grid,
                                const std::vector<DetectionObservation>& observations,
                                const std::vector<std::string>& classes,
                                const SemanticMapOptions& options,
                                const LaserMapCells& laser_map = {});

}  // namespace semchain::semantic
