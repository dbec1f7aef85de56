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
// class prior (shape_fit.h), and parts that are one object are joined (object_association.h).
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

// 'free_space': CV_8UC1 of the grid's size, non-zero where the laser map is free (empty: none).
ExtractedObjects ExtractObjects(const SemanticGrid& grid,
                                const std::vector<DetectionObservation>& observations,
                                const std::vector<std::string>& classes,
                                const SemanticMapOptions& options,
                                const cv::Mat& free_space = cv::Mat());

}  // namespace semchain::semantic
