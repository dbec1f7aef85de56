#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "semantic/detection_points.h"
#include "semantic/grid_geometry.h"
#include "semantic/semantic_grid.h"
#include "semantic/semantic_options.h"
#include "sensors/camera.h"
#include "sensors/detection.h"

// What one camera frame says about the map, kept in the robot frame: computed once from the
// frame's depth image, then posed (and posed again whenever SLAM corrects the frame's pose)
// without reading the image again.
namespace semchain::semantic {

struct RobotDetection {
  Detection detection;
  int class_id = 0;
  std::vector<Eigen::Vector2d> points;  // robot frame, DetectionWorldPoints order
};

struct RobotRay {
  FreeRay ray;  // robot frame
  // Per class: 1 when no box of the class covers the ray's column (its surface then lowers
  // the class, FrameEvidence::undetected).
  std::vector<std::uint8_t> undetected;
};

struct RobotEvidence {
  std::vector<RobotDetection> detections;  // those of a known class with points
  std::vector<RobotRay> rays;
  Eigen::Vector2d camera = Eigen::Vector2d::Zero();  // the camera's position on the robot
};

// 'classes' gives the class ids; detections of other classes and nested duplicates (a box at
// least half inside a larger one of its class) are left out.
RobotEvidence ComputeRobotEvidence(const FrameDetections& frame, const cv::Mat& depth_m,
                                   const std::vector<std::string>& classes,
                                   const MountedCamera& camera, const SemanticMapOptions& options);

// The evidence on the cells of 'lattice' (numbered on it, not clipped to it) for a robot at
// 'pose'.
struct PosedEvidence {
  FrameEvidence grid;
  // The cells of each of RobotEvidence::detections, each once, in cell order.
  std::vector<std::vector<Eigen::Vector2i>> detection_cells;
  Eigen::Vector2i low = Eigen::Vector2i::Zero();  // bounds of all cells (high inclusive)
  Eigen::Vector2i high = Eigen::Vector2i::Constant(-1);

  bool empty() const { return (high.array() < low.array()).any(); }
  // Calls 'visit' with every cell the evidence touches (some more than once).
  template <typename Visit>
  void ForEachCell(Visit&& visit) const {
    for (const auto& hits : grid.hits)
      for (const CellHit& hit : hits) visit(hit.cell);
    for (const auto& cells : grid.undetected)
      for (const Eigen::Vector2i& cell : cells) visit(cell);
    for (const Eigen::Vector2i& cell : grid.free_cells) visit(cell);
  }
};

PosedEvidence PoseEvidence(const RobotEvidence& evidence, const Pose2& pose,
                           const GridGeometry& lattice, int class_count);

}  // namespace semchain::semantic
