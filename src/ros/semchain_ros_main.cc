// semchain_ros: semchain as a ROS 1 node (DESIGN.md §5.7).
//   rosrun semchain semchain_ros _map:=MAP _method:=semantic-scanmatch [_detector:=M.onnx]
//       localization, a drop-in for ROS amcl (ros/localization_node.h)
//   rosrun semchain semchain_ros _mode:=mapping _out:=MAP [_detector:=M.onnx]
//       mapping, a drop-in for slam_gmapping that also maps semantics (ros/mapping_node.h)
#include <ros/ros.h>

#include <string>

#include "ros/localization_node.h"
#include "ros/mapping_node.h"

namespace {

template <typename Node>
int Run(::ros::NodeHandle nh, ::ros::NodeHandle private_nh) {
  semchain::Result<std::unique_ptr<Node>> node = Node::Create(nh, private_nh);
  if (!node.ok()) {
    ROS_FATAL("semchain_ros: %s", node.status().message().c_str());
    return 1;
  }
  ::ros::spin();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  ::ros::init(argc, argv, "semchain_ros");
  ::ros::NodeHandle nh;
  ::ros::NodeHandle private_nh("~");
  std::string mode = "localization";
  if (private_nh.hasParam("mode") && !private_nh.getParam("mode", mode)) {
    ROS_FATAL("semchain_ros: parameter ~mode: wrong type (localization or mapping)");
    return 1;
  }
  if (mode == "localization") return Run<semchain::ros1::LocalizationNode>(nh, private_nh);
  if (mode == "mapping") return Run<semchain::ros1::MappingNode>(nh, private_nh);
  ROS_FATAL("semchain_ros: parameter ~mode: '%s' (localization or mapping)", mode.c_str());
  return 1;
}
