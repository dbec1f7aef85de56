#include "semantic/robot_evidence.h"

#include <algorithm>
#include <map>

namespace semchain::semantic {
namespace {

// Cells in row order, as the grid's evidence lists them.
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

// A box at least half inside a larger box of the same class is the detector seeing part of the
// same object again (one end of a bed beside the box of the whole), not a second object: two
// objects side by side do not nest, and one half hidden behind another of its class is seen
// whole from elsewhere. (With the bar at 0.8 a bed of office_floor was mapped as two halves
// 0.98 m apart: three frames had two boxes on it, 0.49–0.79 of the smaller inside the larger.)
bool IsNestedDuplicate(const Detection& detection, const std::vector<Detection>& frame) {
  constexpr double kInside = 0.5;
  const double area = (detection.box[2] - detection.box[0]) * (detection.box[3] - detection.box[1]);
  for (const Detection& other : frame) {
    if (&other == &detection || other.class_name != detection.class_name) continue;
    const double other_area = (other.box[2] - other.box[0]) * (other.box[3] - other.box[1]);
    if (other_area > area && Intersection(detection, other) >= kInside * area) return true;
  }
  return false;
}

void SortUnique(std::vector<Eigen::Vector2i>& cells) {
  std::sort(cells.begin(), cells.end(), CellKey());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
}

int ClassIndex(const std::vector<std::string>& classes, const std::string& name) {
  const auto it = std::find(classes.begin(), classes.end(), name);
  return it == classes.end() ? -1 : static_cast<int>(it - classes.begin());
}

void Extend(const Eigen::Vector2i& cell, PosedEvidence* posed) {
  if (posed->empty()) {
    posed->low = posed->high = cell;
    return;
  }
  posed->low = posed->low.cwiseMin(cell);
  posed->high = posed->high.cwiseMax(cell);
}

}  // namespace

RobotEvidence ComputeRobotEvidence(const FrameDetections& frame, const cv::Mat& depth_m,
                                   const std::vector<std::string>& classes,
                                   const MountedCamera& camera, const SemanticMapOptions& options) {
  RobotEvidence evidence;
  evidence.camera = camera.robot_from_camera.translation().head<2>();
  for (const Detection& detection : frame.detections) {
    const int c = ClassIndex(classes, detection.class_name);
    const double extent = options.PriorOf(detection.class_name).Extent();
    if (c < 0 || IsNestedDuplicate(detection, frame.detections)) continue;
    // Posed at the origin, the world points are the robot-frame points.
    const std::vector<Eigen::Vector3d> points =
        DetectionWorldPoints(detection, depth_m, camera, Pose2(), extent, options.points);
    if (points.empty()) continue;
    RobotDetection robot{detection, c, {}};
    robot.points.reserve(points.size());
    for (const Eigen::Vector3d& p : points) robot.points.push_back(p.head<2>());
    evidence.detections.push_back(std::move(robot));
  }
  for (const FreeRay& ray : FreeSpaceRays(depth_m, camera, Pose2(), options.free_space)) {
    RobotRay robot{ray, std::vector<std::uint8_t>(classes.size(), 0)};
    for (std::size_t c = 0; c < classes.size(); ++c) {
      const bool boxed =
          std::any_of(frame.detections.begin(), frame.detections.end(), [&](const Detection& d) {
            return d.class_name == classes[c] && ray.column + 0.5 >= d.box[0] &&
                   ray.column + 0.5 <= d.box[2];
          });
      robot.undetected[c] = boxed ? 0 : 1;
    }
    evidence.rays.push_back(std::move(robot));
  }
  return evidence;
}

PosedEvidence PoseEvidence(const RobotEvidence& evidence, const Pose2& pose,
                           const GridGeometry& lattice, int class_count) {
  PosedEvidence posed;
  FrameEvidence& grid = posed.grid;
  grid.hits.resize(static_cast<std::size_t>(class_count));
  grid.undetected.resize(static_cast<std::size_t>(class_count));
  grid.viewer = PosePoint(evidence.camera, pose);
  for (const RobotDetection& detection : evidence.detections) {
    // The detection's points by cell (each cell once per frame: eq. 2 counts observations).
    std::map<Eigen::Vector2i, std::pair<Eigen::Vector2d, int>, CellKey> cells;
    for (const Eigen::Vector2d& robot_point : detection.points) {
      const Eigen::Vector2d p = PosePoint(robot_point, pose);
      auto& [sum, count] = cells[lattice.CellOf(p)];
      if (count == 0) sum.setZero();
      sum += p;
      ++count;
    }
    std::vector<Eigen::Vector2i>& detection_cells = posed.detection_cells.emplace_back();
    for (const auto& [cell, accumulated] : cells) {
      detection_cells.push_back(cell);
      grid.hits[detection.class_id].push_back({cell, accumulated.first / accumulated.second});
      Extend(cell, &posed);
    }
  }
  // Two detections of one class may share a cell: keep it once per class.
  for (std::vector<CellHit>& hits : grid.hits) {
    std::sort(hits.begin(), hits.end(),
              [](const CellHit& a, const CellHit& b) { return CellKey()(a.cell, b.cell); });
    hits.erase(std::unique(hits.begin(), hits.end(),
                           [](const CellHit& a, const CellHit& b) { return a.cell == b.cell; }),
               hits.end());
  }
  // Free space, and the surfaces seen in columns where no box of a class was reported; each
  // cell once, in row order (sorted vectors: a map per cell costs more than the rest).
  std::vector<Eigen::Vector2i>& free = grid.free_cells;
  for (const RobotRay& robot : evidence.rays) {
    const FreeRay ray = PoseRay(robot.ray, pose);
    const std::vector<Eigen::Vector2i> cells = CellsOnSegment(lattice, ray.from, ray.to);
    free.insert(free.end(), cells.begin(), cells.end());
    const Eigen::Vector2i surface = lattice.CellOf(ray.surface);
    for (std::size_t c = 0; c < grid.undetected.size() && c < robot.undetected.size(); ++c) {
      if (robot.undetected[c]) grid.undetected[c].push_back(surface);
    }
  }
  SortUnique(free);
  for (const Eigen::Vector2i& cell : free) Extend(cell, &posed);
  for (std::vector<Eigen::Vector2i>& cells : grid.undetected) {
    SortUnique(cells);
    for (const Eigen::Vector2i& cell : cells) Extend(cell, &posed);
  }
  return posed;
}

}  // namespace semchain::semantic
