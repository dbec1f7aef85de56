#include "detection/class_map.h"

#include <algorithm>

#include "sensors/detection.h"

namespace semchain::detection {
namespace {

// "a, b, c" of at most 'limit' names, then ", ..." ('limit' 0: all).
std::string JoinNames(const std::vector<std::string>& names, std::size_t limit = 0) {
  std::string joined;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (limit > 0 && i == limit) return joined + ", ...";
    joined += (i > 0 ? ", " : "") + names[i];
  }
  return joined;
}

int IndexOf(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

}  // namespace

Result<ClassMap> ParseClassMap(const yaml::Node& root,
                               const std::vector<std::string>& model_classes) {
  if (!root.IsMap()) {
    return root.Error("expected a map of 'model class: semchain class' entries");
  }
  ClassMap map;
  map.classes = DefaultClassNames();
  map.target.assign(model_classes.size(), -1);
  const std::vector<std::string> keys = root.Keys();
  for (const std::string& key : keys) {
    if (IndexOf(model_classes, key) >= 0) continue;
    Result<yaml::Node> value = root.Get(key);
    if (!value.ok()) return value.status();
    return value->Error("not a class of the model (its " + std::to_string(model_classes.size()) +
                        " classes: " + JoinNames(model_classes, 8) + ")");
  }
  SEMCHAIN_RETURN_IF_ERROR(root.CheckKeys(model_classes));  // a key given twice
  for (const std::string& key : keys) {
    Result<yaml::Node> value = root.Get(key);
    if (!value.ok()) return value.status();
    Result<std::string> name = value->AsString();
    if (!name.ok()) return name.status();
    const int target = IndexOf(map.classes, *name);
    if (target < 0) {
      return value->Error("'" + *name + "' is not a semchain class (" + JoinNames(map.classes) +
                          ")");
    }
    map.target[static_cast<std::size_t>(IndexOf(model_classes, key))] = target;
  }
  if (keys.empty()) return root.Error("maps no class");
  return map;
}

Result<ClassMap> LoadClassMap(const std::filesystem::path& path,
                              const std::vector<std::string>& model_classes) {
  Result<yaml::Node> root = yaml::Node::LoadFile(path);
  if (!root.ok()) return root.status();
  return ParseClassMap(*root, model_classes);
}

std::vector<Candidate> MapCandidates(std::vector<Candidate> candidates, const ClassMap& map) {
  std::vector<Candidate> mapped;
  mapped.reserve(candidates.size());
  for (Candidate& candidate : candidates) {
    if (candidate.class_id < 0 || candidate.class_id >= static_cast<int>(map.target.size())) {
      continue;
    }
    const int target = map.target[static_cast<std::size_t>(candidate.class_id)];
    if (target < 0) continue;
    candidate.class_id = target;
    mapped.push_back(candidate);
  }
  return mapped;
}

}  // namespace semchain::detection
