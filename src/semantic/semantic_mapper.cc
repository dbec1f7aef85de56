#include "semantic/semantic_mapper.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/angles.h"
#include "mapping/distance_field.h"
#include "semantic/semantic_chain.h"

namespace semchain::semantic {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool Overlaps(const Eigen::Vector2i& low_a, const Eigen::Vector2i& high_a,
              const Eigen::Vector2i& low_b, const Eigen::Vector2i& high_b) {
  return (low_a.array() <= high_b.array()).all() && (low_b.array() <= high_a.array()).all();
}

LaserMapCells CellsOf(const mapping::MapImage& occupancy) {
  return {mapping::MapCellMask(occupancy, mapping::CellState::kFree),
          mapping::MapCellMask(occupancy, mapping::CellState::kOccupied)};
}

}  // namespace

// The keyframes: frames with a detection on a mapped object, with the objects' chain
// neighbours (seed 000 §3.1 step 2).
struct SemanticMapper::KeyframeDetection {
  int frame = 0;
  const Detection* detection = nullptr;
  int object = -1;
};

bool SemanticMapperOptions::Validate(std::string* error) const {
  if (!(reproject_distance_meters >= 0.0) || !(reproject_angle_radians >= 0.0)) {
    *error = "reproject_distance_meters and reproject_angle_radians must be >= 0";
    return false;
  }
  if (!(full_rebuild_fraction >= 0.0 && full_rebuild_fraction <= 1.0)) {
    *error = "full_rebuild_fraction must be in [0, 1]";
    return false;
  }
  if (grow_margin_cells < 0) {
    *error = "grow_margin_cells must be >= 0";
    return false;
  }
  return true;
}

SemanticMapper::SemanticMapper(const GridGeometry& lattice, std::vector<std::string> classes,
                               const MountedCamera& camera, const SemanticMapOptions& options,
                               const SemanticMapperOptions& mapper_options)
    : classes_(std::move(classes)),
      camera_(camera),
      options_(options),
      mapper_options_(mapper_options),
      grid_(lattice, static_cast<int>(classes_.size()), options.grid) {}

PosedEvidence SemanticMapper::Pose(const FrameRecord& frame, const Pose2& pose) const {
  return PoseEvidence(frame.evidence, pose, grid_.lattice(), static_cast<int>(classes_.size()));
}

// Puts 'posed' (frame at 'pose') on the grid and remembers where it went.
void SemanticMapper::Apply(FrameRecord& frame, const Pose2& pose, PosedEvidence posed) {
  if (!posed.empty()) {
    grid_.GrowToInclude(posed.low, posed.high, mapper_options_.grow_margin_cells);
  }
  grid_.Update(posed.grid);
  frame.pose = pose;
  frame.detection_cells = std::move(posed.detection_cells);
  frame.low = posed.low;
  frame.high = posed.high;
}

RobotEvidence SemanticMapper::ComputeEvidence(const FrameDetections& frame,
                                              const cv::Mat& depth_m) const {
  return ComputeRobotEvidence(frame, depth_m, classes_, camera_, options_);
}

int SemanticMapper::AddFrame(const FrameDetections& frame, const Pose2& pose,
                             const cv::Mat& depth_m) {
  return AddEvidence(frame, ComputeEvidence(frame, depth_m), pose);
}

int SemanticMapper::AddEvidence(const FrameDetections& frame, RobotEvidence evidence,
                                const Pose2& pose) {
  const auto start = std::chrono::steady_clock::now();
  FrameRecord record;
  record.name = frame.frame;
  record.stamp = frame.stamp;
  record.evidence = std::move(evidence);
  Apply(record, pose, Pose(record, pose));
  frames_.push_back(std::move(record));
  statistics_.frame_seconds.push_back(SecondsSince(start));
  return static_cast<int>(frames_.size()) - 1;
}

bool SemanticMapper::Moved(const FrameRecord& frame, const Pose2& pose, bool exact) const {
  if (exact)
    return pose.x != frame.pose.x || pose.y != frame.pose.y || pose.theta != frame.pose.theta;
  return (pose.translation() - frame.pose.translation()).norm() >
             mapper_options_.reproject_distance_meters ||
         std::abs(AngleDifference(pose.theta, frame.pose.theta)) >
             mapper_options_.reproject_angle_radians;
}

int SemanticMapper::Repose(const std::vector<Pose2>& poses, bool exact) {
  std::vector<std::size_t> moved;
  for (std::size_t i = 0; i < frames_.size() && i < poses.size(); ++i) {
    if (Moved(frames_[i], poses[i], exact)) moved.push_back(i);
  }
  if (moved.empty()) return 0;
  const auto start = std::chrono::steady_clock::now();
  const bool full = static_cast<double>(moved.size()) >
                    mapper_options_.full_rebuild_fraction * static_cast<double>(frames_.size());
  Rebuild(moved, poses, full);
  const double seconds = SecondsSince(start);
  ++statistics_.reprojections;
  if (!full) ++statistics_.incremental_reprojections;
  statistics_.reprojected_frames += static_cast<int>(moved.size());
  statistics_.reprojection_seconds += seconds;
  statistics_.max_reprojection_seconds = std::max(statistics_.max_reprojection_seconds, seconds);
  return static_cast<int>(moved.size());
}

// Each cell's value depends only on the evidence that touched it, in frame order: clearing the
// cells the moved frames touch (before and after) and replaying every frame on those cells
// alone gives the grid that a pass over all frames with the new poses gives.
void SemanticMapper::Rebuild(const std::vector<std::size_t>& moved, const std::vector<Pose2>& poses,
                             bool full) {
  if (full) {
    cv::Mat all = grid_.MakeMask();
    all.setTo(1);
    grid_.Clear(all);
    for (std::size_t i = 0; i < frames_.size(); ++i) {
      const Pose2 pose = i < poses.size() ? poses[i] : frames_[i].pose;
      Apply(frames_[i], pose, Pose(frames_[i], pose));
    }
    return;
  }
  std::vector<PosedEvidence> before;
  std::vector<PosedEvidence> after;
  for (const std::size_t i : moved) {
    before.push_back(Pose(frames_[i], frames_[i].pose));
    after.push_back(Pose(frames_[i], poses[i]));
    if (!after.back().empty()) {
      grid_.GrowToInclude(after.back().low, after.back().high, mapper_options_.grow_margin_cells);
    }
  }
  cv::Mat dirty = grid_.MakeMask();
  if (dirty.empty()) {  // no cells at all: nothing to rebuild
    for (std::size_t k = 0; k < moved.size(); ++k) frames_[moved[k]].pose = poses[moved[k]];
    return;
  }
  Eigen::Vector2i low = Eigen::Vector2i::Constant(std::numeric_limits<int>::max());
  Eigen::Vector2i high = Eigen::Vector2i::Constant(std::numeric_limits<int>::min());
  for (const std::vector<PosedEvidence>* list : {&before, &after}) {
    for (const PosedEvidence& posed : *list) {
      if (posed.empty()) continue;
      posed.ForEachCell([&](const Eigen::Vector2i& cell) { grid_.Mark(cell, dirty); });
      low = low.cwiseMin(posed.low);
      high = high.cwiseMax(posed.high);
    }
  }
  grid_.Clear(dirty);
  std::size_t next_moved = 0;
  for (std::size_t i = 0; i < frames_.size(); ++i) {
    FrameRecord& frame = frames_[i];
    if (next_moved < moved.size() && moved[next_moved] == i) {
      grid_.Update(after[next_moved].grid, dirty);
      frame.pose = poses[i];
      frame.detection_cells = std::move(after[next_moved].detection_cells);
      frame.low = after[next_moved].low;
      frame.high = after[next_moved].high;
      ++next_moved;
    } else if (Overlaps(frame.low, frame.high, low, high)) {
      grid_.Update(Pose(frame, frame.pose).grid, dirty);
    }
  }
}

// The detections with cells on a map, in frame order, and where each came from.
struct SemanticMapper::Observations {
  std::vector<DetectionObservation> observations;
  std::vector<KeyframeDetection> sources;
};

SemanticMapper::Observations SemanticMapper::ObservationsOn(const GridGeometry& geometry) const {
  const Eigen::Vector2i offset = grid_.LatticeOffsetOf(geometry);
  Observations on;
  for (std::size_t f = 0; f < frames_.size(); ++f) {
    const FrameRecord& frame = frames_[f];
    for (std::size_t d = 0; d < frame.evidence.detections.size(); ++d) {
      const RobotDetection& detection = frame.evidence.detections[d];
      DetectionObservation observation{
          static_cast<int>(f), detection.class_id, detection.detection.score, {}};
      for (const Eigen::Vector2i& cell : frame.detection_cells[d]) {
        if (geometry.Contains(cell - offset)) observation.cells.push_back(cell - offset);
      }
      if (observation.cells.empty()) continue;
      on.observations.push_back(std::move(observation));
      on.sources.push_back({static_cast<int>(f), &detection.detection, -1});
    }
  }
  return on;
}

int SemanticMapper::CountObjects(const mapping::MapImage& occupancy) const {
  const GridGeometry geometry = GeometryOf(occupancy);
  const Observations on = ObservationsOn(geometry);
  return static_cast<int>(
      ExtractObjects(grid_.Crop(geometry), on.observations, classes_, options_, CellsOf(occupancy))
          .objects.size());
}

SemanticMappingResult SemanticMapper::Snapshot(const mapping::MapImage& occupancy) const {
  const GridGeometry geometry = GeometryOf(occupancy);
  const SemanticGrid grid = grid_.Crop(geometry);
  Observations on = ObservationsOn(geometry);
  const std::vector<DetectionObservation>& observations = on.observations;
  std::vector<KeyframeDetection>& sources = on.sources;
  const ExtractedObjects extracted =
      ExtractObjects(grid, observations, classes_, options_, CellsOf(occupancy));
  SemanticMappingResult result;
  result.map.classes = classes_;
  result.map.objects = extracted.objects;
  int max_id = -1;
  for (const SemanticObject& object : extracted.objects) max_id = std::max(max_id, object.id);
  result.first_frame.assign(static_cast<std::size_t>(max_id + 1), -1);
  Viewpoints viewpoints;
  for (std::size_t o = 0; o < sources.size(); ++o) {
    const int id = extracted.observation_object[o];
    sources[o].object = id;
    if (id < 0) continue;
    viewpoints[id].push_back(
        frames_[static_cast<std::size_t>(sources[o].frame)].pose.translation());
    int& first = result.first_frame[static_cast<std::size_t>(id)];
    if (first < 0) first = sources[o].frame;
  }
  BuildChainsAndNeighbours(occupancy, options_.chain, viewpoints, &result.map);
  result.frames = frame_count();
  result.detections = static_cast<int>(observations.size());

  std::size_t o = 0;
  for (std::size_t f = 0; f < frames_.size(); ++f) {
    const FrameRecord& frame = frames_[f];
    Keyframe keyframe{frame.name, frame.stamp, frame.pose, {}};
    for (; o < sources.size() && sources[o].frame == static_cast<int>(f); ++o) {
      const int id = sources[o].object;
      if (id < 0) continue;
      const Detection& detection = *sources[o].detection;
      KeyframeObject object;
      object.id = id;
      object.class_name = detection.class_name;
      std::copy(std::begin(detection.box), std::end(detection.box), object.box);
      object.depth_m = detection.depth_m;
      ChainNeighbours neighbours;
      if (FindChainNeighbours(result.map, id, &neighbours)) {
        object.upstream = neighbours.upstream;
        object.downstream = neighbours.downstream;
      }
      keyframe.objects.push_back(object);
    }
    if (!keyframe.objects.empty()) result.keyframes.push_back(std::move(keyframe));
  }
  return result;
}

}  // namespace semchain::semantic
