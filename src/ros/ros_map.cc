#include "ros/ros_map.h"

#include "ros/ros_geometry.h"

namespace semchain::ros1 {

nav_msgs::OccupancyGrid ToOccupancyGridMsg(const mapping::MapImage& map,
                                           const std::string& frame_id) {
  nav_msgs::OccupancyGrid grid;
  grid.header.frame_id = frame_id;
  grid.info.resolution = static_cast<float>(map.resolution);
  grid.info.width = static_cast<std::uint32_t>(map.width);
  grid.info.height = static_cast<std::uint32_t>(map.height);
  grid.info.origin = ToPoseMsg(Pose2(map.origin.x(), map.origin.y(), map.origin.z()));
  grid.data = map.cells;
  return grid;
}

}  // namespace semchain::ros1
