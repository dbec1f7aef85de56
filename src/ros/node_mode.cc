#include "ros/node_mode.h"

#include <algorithm>

namespace semchain::ros1 {

CommandLineParameters::CommandLineParameters(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    const std::size_t assign = argument.find(":=");
    if (assign == std::string::npos || assign < 2 || argument[0] != '_' || argument[1] == '_') {
      continue;
    }
    names_.push_back(argument.substr(1, assign - 1));
  }
}

bool CommandLineParameters::Has(const std::string& name) const {
  return std::find(names_.begin(), names_.end(), name) != names_.end();
}

void CommandLineParameters::NoteValues(const ::ros::NodeHandle& private_nh) {
  noted_.clear();
  for (const std::string& name : names_) {
    XmlRpc::XmlRpcValue value;
    if (private_nh.getParam(name, value)) noted_.emplace_back(name, value);
  }
}

std::vector<std::string> CommandLineParameters::Forget(const ::ros::NodeHandle& private_nh) const {
  std::vector<std::string> forgotten;
  for (const auto& [name, noted] : noted_) {
    XmlRpc::XmlRpcValue now;
    if (!private_nh.getParam(name, now) || now != noted) continue;
    if (private_nh.deleteParam(name)) forgotten.push_back(name);
  }
  return forgotten;
}

Result<NodeMode> ReadNodeMode(const ::ros::NodeHandle& private_nh,
                              const CommandLineParameters& command_line) {
  NodeMode mode;
  if (!private_nh.hasParam("mode")) return mode;
  if (!private_nh.getParam("mode", mode.name)) {
    return Status::Error("parameter ~mode: wrong type (localization or mapping)");
  }
  if (mode.name != "localization" && mode.name != "mapping") {
    return Status::Error("parameter ~mode: '" + mode.name + "' (localization or mapping)");
  }
  mode.source = command_line.Has("mode") ? "command line" : "parameter server";
  // A command line made for the other mode, under a ~mode it did not give, is an earlier run's
  // ~mode left behind (or a launch file's): refused rather than followed.
  const char* other = mode.name == "mapping" ? "map" : "out";
  if (mode.source == "parameter server" && command_line.Has(other)) {
    return Status::Error("parameter ~mode: '" + mode.name +
                         "' is on the parameter server (an earlier run's?) but this command "
                         "line gives _" +
                         other + ":=, a parameter of the other mode; give _mode:=" +
                         (mode.name == "mapping" ? "localization" : "mapping") +
                         " or delete it (rosparam delete " + private_nh.resolveName("mode") + ")");
  }
  return mode;
}

}  // namespace semchain::ros1
