#include "localization/standable_space.h"

#include <opencv2/imgproc.hpp>

#include "mapping/distance_field.h"
#include "semantic/semantic_chain.h"

namespace semchain::localization {

StandableSpace::StandableSpace(const mapping::MapImage& occupancy, double clearance,
                               double unknown_reach)
    : occupancy_(occupancy), clearance_meters_(clearance), unknown_reach_(unknown_reach) {
  if (occupancy.width > 0 && occupancy.height > 0) {
    const cv::Mat free = mapping::MapCellMask(occupancy, mapping::CellState::kFree);
    cv::distanceTransform(free, clearance_, cv::DIST_L2, cv::DIST_MASK_PRECISE);
    clearance_ *= occupancy.resolution;
    if (unknown_reach_ > 0.0) {  // only Standable reads it, and only then
      cv::Mat not_free;
      cv::bitwise_not(free, not_free);
      cv::distanceTransform(not_free, to_free_, cv::DIST_L2, cv::DIST_MASK_PRECISE);
      to_free_ *= occupancy.resolution;
    }
  }
}

std::optional<Eigen::Vector2i> StandableSpace::MapCell(const Eigen::Vector2d& point) const {
  const semantic::GridGeometry geometry = semantic::GeometryOf(occupancy_);
  const Eigen::Vector2i cell = geometry.CellOf(point);
  if (!geometry.Contains(cell)) return std::nullopt;
  return cell;
}

bool StandableSpace::InFreeSpace(const Eigen::Vector2d& point) const {
  if (clearance_.empty()) return false;
  const std::optional<Eigen::Vector2i> cell = MapCell(point);
  if (!cell) return false;
  // The distance to the nearest non-free cell is 0 exactly on the cells that are not free.
  const float clearance = clearance_.at<float>(cell->y(), cell->x());
  return clearance > 0.0f && clearance >= clearance_meters_;
}

bool StandableSpace::OffObstacles(const Eigen::Vector2d& point) const {
  const std::optional<Eigen::Vector2i> cell = MapCell(point);
  return cell && mapping::ClassifyMapCell(occupancy_, cell->x(), cell->y()) !=
                     mapping::CellState::kOccupied;
}

bool StandableSpace::Standable(const Eigen::Vector2d& point) const {
  if (InFreeSpace(point)) return true;
  if (unknown_reach_ <= 0.0 || to_free_.empty()) return false;
  const std::optional<Eigen::Vector2i> cell = MapCell(point);
  return cell &&
         mapping::ClassifyMapCell(occupancy_, cell->x(), cell->y()) ==
             mapping::CellState::kUnknown &&
         to_free_.at<float>(cell->y(), cell->x()) <= unknown_reach_;
}

}  // namespace semchain::localization
