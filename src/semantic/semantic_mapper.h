#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "mapping/map_io.h"
#include "semantic/keyframes.h"
#include "semantic/object_extraction.h"
#include "semantic/semantic_grid.h"
#include "semantic/semantic_map.h"
#include "semantic/semantic_options.h"
#include "sensors/camera.h"
#include "sensors/detection.h"

// Semantic mapping (DESIGN.md §3.4–3.5) one camera frame at a time: each frame's detections
// and depth image, posed by SLAM, update the Bayesian semantic grid; Finish() extracts the
// objects, builds the chains and the neighbour graph, and lists the keyframes.
namespace semchain::semantic {

struct SemanticMappingResult {
  SemanticMap map;
  std::vector<Keyframe> keyframes;
  int frames = 0;
  int detections = 0;  // used (score above the minimum, with points on the map)
};

class SemanticMapper {
 public:
  // 'occupancy' is the SLAM map; the semantic grid has its cells. 'classes' fixes the class
  // order of the layers and of semantic.json (detections of other classes are ignored).
  SemanticMapper(const mapping::MapImage& occupancy, std::vector<std::string> classes,
                 const MountedCamera& camera, const SemanticMapOptions& options);

  // One frame seen from robot pose 'pose'; 'depth_m' is CV_32FC1 in metres (0 = none) and of
  // the camera's size.
  void AddFrame(const FrameDetections& frame, const Pose2& pose, const cv::Mat& depth_m);

  SemanticMappingResult Finish() const;

  const SemanticGrid& grid() const { return grid_; }

 private:
  struct FrameRecord {
    std::string name;
    double stamp = 0.0;
    Pose2 pose;
    // Detections that gave points, with the index of their observation.
    std::vector<std::pair<Detection, int>> detections;
  };

  int ClassIndex(const std::string& name) const;

  mapping::MapImage occupancy_;
  std::vector<std::string> classes_;
  MountedCamera camera_;
  SemanticMapOptions options_;
  SemanticGrid grid_;
  std::vector<DetectionObservation> observations_;
  std::vector<FrameRecord> frames_;
};

}  // namespace semchain::semantic
