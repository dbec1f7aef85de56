#pragma once

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/status.h"

// A strict reader for configuration and world files (DESIGN.md §5.2). Every node remembers the
// file it came from and its key path, so that each error is one line naming file, line and key:
//   "world.yaml:12: objects[2].radius: 'abc' is not a number".
// Numbers are parsed strictly ("1.5x", "", "nan" and "inf" are errors) and CheckKeys() turns a
// misspelt key into an error, so a typo never silently changes an experiment.
namespace semchain::yaml {

class Node {
 public:
  // An empty (null) node, e.g. a member to be filled in later.
  Node();

  // Parses a file; an unreadable file or a YAML syntax error is "file:line: message".
  static Result<Node> LoadFile(const std::filesystem::path& path);
  // Parses 'text'; 'source_name' stands for the file in error messages.
  static Result<Node> LoadString(const std::string& text, const std::string& source_name);

  bool IsMap() const { return node_.IsMap(); }
  bool IsSequence() const { return node_.IsSequence(); }
  bool IsScalar() const { return node_.IsScalar(); }
  bool IsNull() const { return !node_.IsDefined() || node_.IsNull(); }
  // Number of entries of a map or sequence, 0 otherwise.
  std::size_t size() const;

  // True when this is a map with 'key'.
  bool Has(const std::string& key) const;
  // The value at 'key' of this map; a missing key is "file:line: path.key: missing".
  Result<Node> Get(const std::string& key) const;
  // Element 'index' of this sequence (path "walls[2]"); 'index' must be < size().
  Node At(std::size_t index) const;
  // The keys of this map in file order (empty for anything else).
  std::vector<std::string> Keys() const;

  // Scalar conversions; errors name the value: "file:line: path: 'abc' is not a number".
  Result<double> AsDouble() const;  // finite numbers only
  Result<int> AsInt() const;
  Result<bool> AsBool() const;  // true/True/TRUE/false/False/FALSE (YAML 1.2 core schema)
  Result<std::string> AsString() const;
  // A sequence of numbers; 'expected_size' 0 accepts any length.
  Result<std::vector<double>> AsDoubleList(std::size_t expected_size = 0) const;

  // Fails on the first key of this map that is not in 'allowed' (or appears twice):
  // "file:line: robot.lidar.hieght: unknown key (allowed: height, beams, ...)".
  Status CheckKeys(const std::vector<std::string>& allowed) const;

  // "file:line: path", the prefix of every error about this node ("file:line" at the root).
  std::string Where() const;
  // An error about this node: Where() + ": " + message.
  Status Error(const std::string& message) const;
  // The key path from the document root, e.g. "robot.lidar.height" or "walls[2]".
  const std::string& path() const { return path_; }
  const std::string& source() const { return *source_; }

 private:
  Node(YAML::Node node, std::shared_ptr<const std::string> source, std::string path,
       YAML::Mark mark);

  std::string ChildPath(const std::string& key) const;
  // "a map", "a sequence", "nothing", "'text'": what this node is, for error messages.
  std::string Describe() const;
  // The scalar text, or an error saying that a scalar of 'kind' was expected.
  Result<std::string> ScalarText(const char* kind) const;

  YAML::Node node_;
  std::shared_ptr<const std::string> source_;
  std::string path_;
  // Where this node is; for a missing key, where its map is.
  YAML::Mark mark_;
};

// Optional-with-default readers: when 'map' has no 'key', '*value' is left untouched (it holds
// the default); when it has, the value must convert or the error is returned. 'map' must be a
// map (or null, which counts as empty).
Status ReadOptional(const Node& map, const std::string& key, double* value);
Status ReadOptional(const Node& map, const std::string& key, int* value);
Status ReadOptional(const Node& map, const std::string& key, bool* value);
Status ReadOptional(const Node& map, const std::string& key, std::string* value);
Status ReadOptional(const Node& map, const std::string& key, std::vector<double>* value);

}  // namespace semchain::yaml
