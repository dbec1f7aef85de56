#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "mapping/map_io.h"
#include "semantic/keyframes.h"
#include "semantic/object_extraction.h"
#include "semantic/robot_evidence.h"
#include "semantic/semantic_grid.h"
#include "semantic/semantic_map.h"
#include "semantic/semantic_options.h"
#include "sensors/camera.h"
#include "sensors/detection.h"

// Semantic mapping (DESIGN.md §3.4–3.5) one camera frame at a time, online: each frame's
// detections and depth image, posed by SLAM, update the Bayesian semantic grid (seed 001
// eq. 1–2); Snapshot() extracts the objects, builds the chains and the neighbour graph, and
// lists the keyframes on any occupancy map, at any moment. The grid grows with the evidence
// (the SLAM map grows while the robot drives). Each frame's evidence is kept in the robot
// frame, so that when SLAM corrects the trajectory (Repose) the frames that moved are
// re-projected: only the cells they touch are rebuilt, or the whole grid where most frames
// moved. The batch `semchain semantic` is this mapper fed a whole run on a fixed trajectory.
namespace semchain::semantic {

struct SemanticMappingResult {
  SemanticMap map;
  std::vector<Keyframe> keyframes;
  int frames = 0;
  int detections = 0;  // used (score above the minimum, with points on the map)
  // For each object (by id), the index of the first frame that saw it.
  std::vector<int> first_frame;
};

struct SemanticMapperOptions {
  // A frame is re-projected when its pose moved farther than this since it was put on the
  // grid (metres, radians; the default 0.05 m is one cell, 1°).
  double reproject_distance_meters = 0.05;
  double reproject_angle_radians = 0.017453292519943295;
  // When more than this fraction of the frames moved, the whole grid is rebuilt instead of
  // the cells the moved frames touch.
  double full_rebuild_fraction = 0.5;
  // The grid grows by this many cells beyond the evidence, so that it grows seldom.
  int grow_margin_cells = 40;

  bool Validate(std::string* error) const;
};

// Cost of the mapper over a run.
struct SemanticMapperStatistics {
  std::vector<double> frame_seconds;  // per frame: posing its evidence and updating the grid
  int reprojections = 0;              // Repose calls that moved something
  int incremental_reprojections = 0;  // of which rebuilt only the touched cells
  int reprojected_frames = 0;         // frames re-posed, summed over the reprojections
  double reprojection_seconds = 0.0;
  double max_reprojection_seconds = 0.0;
};

class SemanticMapper {
 public:
  // 'lattice' numbers the cells (the first SLAM map; the grid grows from it). 'classes' fixes
  // the class order of the layers and of semantic.json (detections of other classes are
  // ignored).
  SemanticMapper(const GridGeometry& lattice, std::vector<std::string> classes,
                 const MountedCamera& camera, const SemanticMapOptions& options,
                 const SemanticMapperOptions& mapper_options = {});
  SemanticMapper(const SemanticMapper&) = delete;
  SemanticMapper& operator=(const SemanticMapper&) = delete;

  // One frame seen from robot pose 'pose'; 'depth_m' is CV_32FC1 in metres (0 = none) and of
  // the camera's size. Returns the frame's index.
  int AddFrame(const FrameDetections& frame, const Pose2& pose, const cv::Mat& depth_m);
  // What AddFrame does with the depth image, which needs no pose (so it can be done ahead,
  // e.g. while SLAM runs); AddEvidence then puts it on the grid.
  RobotEvidence ComputeEvidence(const FrameDetections& frame, const cv::Mat& depth_m) const;
  int AddEvidence(const FrameDetections& frame, RobotEvidence evidence, const Pose2& pose);

  // The frames' poses now ('poses[i]' for frame i; fewer poses leave the later frames alone).
  // Frames that moved beyond the tolerance (any move when 'exact') are re-projected; returns
  // how many.
  int Repose(const std::vector<Pose2>& poses, bool exact = false);

  // The semantic map, keyframes and counts on 'occupancy' (a map on the lattice's grid: its
  // free space cleans the objects, its regions order the chains).
  SemanticMappingResult Snapshot(const mapping::MapImage& occupancy) const;

  // The number of objects on 'occupancy' now (the extraction of Snapshot without the chains
  // and keyframes).
  int CountObjects(const mapping::MapImage& occupancy) const;

  int frame_count() const { return static_cast<int>(frames_.size()); }
  // The pose frame 'i' is on the grid with.
  const Pose2& frame_pose(int i) const { return frames_[static_cast<std::size_t>(i)].pose; }
  double frame_stamp(int i) const { return frames_[static_cast<std::size_t>(i)].stamp; }
  const std::vector<std::string>& classes() const { return classes_; }
  const SemanticGrid& grid() const { return grid_; }
  const SemanticMapperStatistics& statistics() const { return statistics_; }

 private:
  struct FrameRecord {
    std::string name;
    double stamp = 0.0;
    Pose2 pose;
    RobotEvidence evidence;
    // Per RobotEvidence::detections, its cells at 'pose'.
    std::vector<std::vector<Eigen::Vector2i>> detection_cells;
    Eigen::Vector2i low = Eigen::Vector2i::Zero();  // bounds of its cells at 'pose'
    Eigen::Vector2i high = Eigen::Vector2i::Constant(-1);
  };

  struct KeyframeDetection;
  struct Observations;
  Observations ObservationsOn(const GridGeometry& geometry) const;
  PosedEvidence Pose(const FrameRecord& frame, const Pose2& pose) const;
  void Apply(FrameRecord& frame, const Pose2& pose, PosedEvidence posed);
  bool Moved(const FrameRecord& frame, const Pose2& pose, bool exact) const;
  void Rebuild(const std::vector<std::size_t>& moved, const std::vector<Pose2>& poses, bool full);

  std::vector<std::string> classes_;
  MountedCamera camera_;
  SemanticMapOptions options_;
  SemanticMapperOptions mapper_options_;
  SemanticGrid grid_;
  std::vector<FrameRecord> frames_;
  SemanticMapperStatistics statistics_;
};

}  // namespace semchain::semantic
