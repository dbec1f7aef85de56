#pragma once

#include <ros/node_handle.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <string>
#include <utility>
#include <vector>

#include "core/status.h"

// Which mode semchain_ros runs in (~mode), where that came from, and the private parameters
// of its own command line.
//
// roscpp puts a command line's `_name:=value` on the parameter server as ~name, and it stays
// there after the node exits: a later `semchain_ros _map:=lab_map` would find the earlier run's
// `_mode:=mapping` (and its ~out, ~detector, ...) and silently map instead of localizing. So the
// node forgets, when it exits, the private parameters its own command line set (those still
// holding the value it set): a command line's parameters apply to that run only. Parameters set
// otherwise (a launch file's <param>, `rosparam set`) are left alone, as amcl leaves its own: a
// respawned node needs them. The launch files set ~mode themselves, and the start-up line says
// the mode and where it came from, so a mode left behind by a run that did not exit cleanly
// shows; one that contradicts the command line stops the node (ReadNodeMode).
namespace semchain::ros1 {

// The private parameters given on a command line, read before ros::init removes them from argv.
class CommandLineParameters {
 public:
  // The names of the `_name:=value` arguments of argv ('__name:=' are roscpp's own).
  CommandLineParameters(int argc, char** argv);

  bool Has(const std::string& name) const;
  // Notes the value each has on the parameter server now (after ros::init put it there).
  void NoteValues(const ::ros::NodeHandle& private_nh);
  // Deletes those of the parameters that still hold the noted value (another node of the same
  // name may have set its own since); returns the names deleted.
  std::vector<std::string> Forget(const ::ros::NodeHandle& private_nh) const;

 private:
  std::vector<std::string> names_;
  std::vector<std::pair<std::string, XmlRpc::XmlRpcValue>> noted_;
};

struct NodeMode {
  std::string name = "localization";  // "localization" or "mapping"
  // Where it came from, for the start-up line: "default", "command line" or "parameter server".
  std::string source = "default";

  std::string Describe() const { return name + " (~mode: " + source + ")"; }
};

// ~mode; an unknown mode or a value of another type is an error naming the parameter, and so is
// a ~mode from the parameter server when the command line gives the other mode's main parameter
// (_map:= under a mapping ~mode, _out:= under a localization one).
Result<NodeMode> ReadNodeMode(const ::ros::NodeHandle& private_nh,
                              const CommandLineParameters& command_line);

}  // namespace semchain::ros1
