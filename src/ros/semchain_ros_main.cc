// semchain_ros: the semchain localizer as a ROS 1 node, a drop-in for ROS amcl (DESIGN.md §5.7).
//   rosrun semchain semchain_ros _map:=MAP _method:=semantic-scanmatch [_detector:=M.onnx]
// See ros/localization_node.h for its topics, parameters and service.
#include <ros/ros.h>

#include "ros/localization_node.h"

int main(int argc, char** argv) {
  ::ros::init(argc, argv, "semchain_ros");
  ::ros::NodeHandle nh;
  ::ros::NodeHandle private_nh("~");
  semchain::Result<std::unique_ptr<semchain::ros1::LocalizationNode>> node =
      semchain::ros1::LocalizationNode::Create(nh, private_nh);
  if (!node.ok()) {
    ROS_FATAL("semchain_ros: %s", node.status().message().c_str());
    return 1;
  }
  ::ros::spin();
  return 0;
}
