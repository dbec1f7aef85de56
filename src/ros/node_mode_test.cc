#include "ros/node_mode.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace semchain::ros1 {
namespace {

CommandLineParameters Parse(std::vector<std::string> arguments) {
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  return CommandLineParameters(static_cast<int>(argv.size()), argv.data());
}

// Only `_name:=value` sets a private parameter: `__name:=` are roscpp's own (__name, __ns,
// __log), `from:=to` is a remapping and a bare word is an argument.
TEST(CommandLineParametersTest, TakesThePrivateParametersOnly) {
  const CommandLineParameters parameters =
      Parse({"semchain_ros", "_mode:=mapping", "_out:=/tmp/a:=b", "__name:=other", "scan:=/front",
             "_seed", "_:=x", "_detector:="});
  EXPECT_TRUE(parameters.Has("mode"));
  EXPECT_TRUE(parameters.Has("out"));
  EXPECT_TRUE(parameters.Has("detector"));
  EXPECT_FALSE(parameters.Has("name"));
  EXPECT_FALSE(parameters.Has("_name"));
  EXPECT_FALSE(parameters.Has("scan"));
  EXPECT_FALSE(parameters.Has("seed"));
  EXPECT_FALSE(parameters.Has(""));
  EXPECT_FALSE(parameters.Has("semchain_ros"));
}

}  // namespace
}  // namespace semchain::ros1
