#include "semantic/semantic_mapper.h"

#include <algorithm>
#include <map>
#include <unordered_map>

#include "core/transforms.h"
#include "mapping/distance_field.h"
#include "semantic/detection_points.h"
#include "semantic/semantic_chain.h"

namespace semchain::semantic {
namespace {

struct CellKey {
  bool operator()(const Eigen::Vector2i& a, const Eigen::Vector2i& b) const {
    return a.y() != b.y() ? a.y() < b.y() : a.x() < b.x();
  }
};

// The area of box 'a' that lies inside box 'b' (pixels²).
double Intersection(const Detection& a, const Detection& b) {
  const double w = std::min(a.box[2], b.box[2]) - std::max(a.box[0], b.box[0]);
  const double h = std::min(a.box[3], b.box[3]) - std::max(a.box[1], b.box[1]);
  return w > 0.0 && h > 0.0 ? w * h : 0.0;
}

// A box mostly inside a larger box of the same class is the detector seeing part of the same
// object again (one face of it), not a second object: two objects side by side do not nest.
bool IsNestedDuplicate(const Detection& detection, const std::vector<Detection>& frame) {
  constexpr double kInside = 0.8;
  const double area = (detection.box[2] - detection.box[0]) * (detection.box[3] - detection.box[1]);
  for (const Detection& other : frame) {
    if (&other == &detection || other.class_name != detection.class_name) continue;
    const double other_area = (other.box[2] - other.box[0]) * (other.box[3] - other.box[1]);
    if (other_area > area && Intersection(detection, other) >= kInside * area) return true;
  }
  return false;
}

}  // namespace

SemanticMapper::SemanticMapper(const mapping::MapImage& occupancy, std::vector<std::string> classes,
                               const MountedCamera& camera, const SemanticMapOptions& options)
    : occupancy_(occupancy),
      classes_(std::move(classes)),
      camera_(camera),
      options_(options),
      grid_(GeometryOf(occupancy), static_cast<int>(classes_.size()), options.grid) {}

int SemanticMapper::ClassIndex(const std::string& name) const {
  const auto it = std::find(classes_.begin(), classes_.end(), name);
  return it == classes_.end() ? -1 : static_cast<int>(it - classes_.begin());
}

void SemanticMapper::AddFrame(const FrameDetections& frame, const Pose2& pose,
                              const cv::Mat& depth_m) {
  const GridGeometry& geometry = grid_.geometry();
  FrameRecord record{frame.frame, frame.stamp, pose, {}};
  FrameEvidence evidence;
  evidence.hits.resize(classes_.size());
  evidence.viewer = RobotToWorld(pose, camera_.robot_from_camera.translation()).head<2>();
  const int frame_index = static_cast<int>(frames_.size());
  for (const Detection& detection : frame.detections) {
    const int c = ClassIndex(detection.class_name);
    if (c < 0 || IsNestedDuplicate(detection, frame.detections)) continue;
    const std::vector<Eigen::Vector3d> points =
        DetectionWorldPoints(detection, depth_m, camera_, pose,
                             options_.PriorOf(detection.class_name).Extent(), options_.points);
    // The detection's points by cell (each cell once per frame: eq. 2 counts observations).
    std::map<Eigen::Vector2i, std::pair<Eigen::Vector2d, int>, CellKey> cells;
    for (const Eigen::Vector3d& p : points) {
      const Eigen::Vector2i cell = geometry.CellOf(p.head<2>());
      if (!geometry.Contains(cell)) continue;
      auto& [sum, count] = cells[cell];
      if (count == 0) sum.setZero();
      sum += p.head<2>();
      ++count;
    }
    if (cells.empty()) continue;
    DetectionObservation observation{frame_index, c, detection.score, {}};
    for (const auto& [cell, accumulated] : cells) {
      observation.cells.push_back(cell);
      evidence.hits[c].push_back({cell, accumulated.first / accumulated.second});
    }
    record.detections.emplace_back(detection, static_cast<int>(observations_.size()));
    observations_.push_back(std::move(observation));
  }
  // Two detections of one class may share a cell: keep it once per class.
  for (std::vector<CellHit>& hits : evidence.hits) {
    std::sort(hits.begin(), hits.end(),
              [](const CellHit& a, const CellHit& b) { return CellKey()(a.cell, b.cell); });
    hits.erase(std::unique(hits.begin(), hits.end(),
                           [](const CellHit& a, const CellHit& b) { return a.cell == b.cell; }),
               hits.end());
  }
  // Free space, and the surfaces seen in columns where no box of a class was reported.
  std::map<Eigen::Vector2i, bool, CellKey> free;
  std::vector<std::map<Eigen::Vector2i, bool, CellKey>> undetected(classes_.size());
  for (const FreeRay& ray : FreeSpaceRays(depth_m, camera_, pose, options_.free_space)) {
    for (const Eigen::Vector2i& cell : CellsOnSegment(geometry, ray.from, ray.to))
      free[cell] = true;
    const Eigen::Vector2i surface = geometry.CellOf(ray.surface);
    if (!geometry.Contains(surface)) continue;
    for (std::size_t c = 0; c < classes_.size(); ++c) {
      const bool boxed =
          std::any_of(frame.detections.begin(), frame.detections.end(), [&](const Detection& d) {
            return d.class_name == classes_[c] && ray.column + 0.5 >= d.box[0] &&
                   ray.column + 0.5 <= d.box[2];
          });
      if (!boxed) undetected[c][surface] = true;
    }
  }
  for (const auto& [cell, unused] : free) evidence.free_cells.push_back(cell);
  evidence.undetected.resize(classes_.size());
  for (std::size_t c = 0; c < classes_.size(); ++c) {
    for (const auto& [cell, unused] : undetected[c]) evidence.undetected[c].push_back(cell);
  }
  grid_.Update(evidence);
  frames_.push_back(std::move(record));
}

SemanticMappingResult SemanticMapper::Finish() const {
  SemanticMappingResult result;
  const ExtractedObjects extracted =
      ExtractObjects(grid_, observations_, classes_, options_,
                     mapping::MapCellMask(occupancy_, mapping::CellState::kFree));
  result.map.classes = classes_;
  result.map.objects = extracted.objects;
  Viewpoints viewpoints;
  for (const FrameRecord& frame : frames_) {
    for (const auto& [detection, observation] : frame.detections) {
      const int id = extracted.observation_object[observation];
      if (id >= 0) viewpoints[id].push_back(frame.pose.translation());
    }
  }
  BuildChainsAndNeighbours(occupancy_, options_.chain, viewpoints, &result.map);
  result.frames = static_cast<int>(frames_.size());
  result.detections = static_cast<int>(observations_.size());

  for (const FrameRecord& frame : frames_) {
    Keyframe keyframe{frame.name, frame.stamp, frame.pose, {}};
    for (const auto& [detection, observation] : frame.detections) {
      const int id = extracted.observation_object[observation];
      if (id < 0) continue;
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
