// semchain_ros: semchain as a ROS 1 node (DESIGN.md §5.7).
//   rosrun semchain semchain_ros _map:=MAP _method:=semantic-scanmatch [_detector:=M.onnx]
//       localization, a drop-in for ROS amcl (ros/localization_node.h)
//   rosrun semchain semchain_ros _mode:=mapping _out:=MAP [_detector:=M.onnx]
//       mapping, a drop-in for slam_gmapping that also maps semantics (ros/mapping_node.h)
// The command line's `_name:=value` parameters apply to this run only: the node deletes them
// from the parameter server when it exits (ros/node_mode.h).
#include <ros/ros.h>

#include <cstdio>
#include <string>
#include <vector>

#include "ros/localization_node.h"
#include "ros/mapping_node.h"
#include "ros/node_mode.h"

namespace {

template <typename Node>
int Run(::ros::NodeHandle nh, ::ros::NodeHandle private_nh, const semchain::ros1::NodeMode& mode) {
  semchain::Result<std::unique_ptr<Node>> node = Node::Create(nh, private_nh, mode);
  if (!node.ok()) {
    ROS_FATAL("semchain_ros: %s", node.status().message().c_str());
    return 1;
  }
  ::ros::spin();
  return 0;
}

int RunMode(::ros::NodeHandle nh, ::ros::NodeHandle private_nh,
            const semchain::ros1::CommandLineParameters& command_line) {
  const semchain::Result<semchain::ros1::NodeMode> mode =
      semchain::ros1::ReadNodeMode(private_nh, command_line);
  if (!mode.ok()) {
    ROS_FATAL("semchain_ros: %s", mode.status().message().c_str());
    return 1;
  }
  if (mode->name == "mapping") return Run<semchain::ros1::MappingNode>(nh, private_nh, *mode);
  return Run<semchain::ros1::LocalizationNode>(nh, private_nh, *mode);
}

}  // namespace

int main(int argc, char** argv) {
  semchain::ros1::CommandLineParameters command_line(argc, argv);  // before ros::init takes them
  ::ros::init(argc, argv, "semchain_ros");
  ::ros::NodeHandle nh;
  ::ros::NodeHandle private_nh("~");
  command_line.NoteValues(private_nh);
  const int status = RunMode(nh, private_nh, command_line);
  const std::vector<std::string> forgotten = command_line.Forget(private_nh);
  if (!forgotten.empty()) {
    std::string names;
    for (const std::string& name : forgotten) names += (names.empty() ? "~" : ", ~") + name;
    // roscpp's console is shut down by now.
    std::printf(
        "semchain_ros: deleted the command line's %s from the parameter server (they "
        "apply to one run)\n",
        names.c_str());
  }
  return status;
}
