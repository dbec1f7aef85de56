#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/status.h"
#include "detection/yolo_head.h"
#include "io/yaml_reader.h"

// A model's classes mapped to semchain's (`--class-map FILE`, the ROS nodes' ~class_map), so that
// a detector trained on another label set (COCO: config/classes/coco.yaml) feeds the semantic
// map. The file is a YAML map, one entry per model class used:
//   tv: computer          # model class: semchain class
//   laptop: computer      # several model classes may map to one semchain class
// Model classes it does not name are dropped.
namespace semchain::detection {

struct ClassMap {
  std::vector<std::string> classes;  // the classes mapped to: semchain's (DefaultClassNames())
  std::vector<int> target;           // per model class: its index in 'classes', or -1 (dropped)
};

// Reads 'root' (a parsed class-map file) for a model with 'model_classes'. A key that is not one
// of the model's classes, a value that is not one of semchain's classes, a key given twice or
// an empty map is an error naming the file, the line and the key.
Result<ClassMap> ParseClassMap(const yaml::Node& root,
                               const std::vector<std::string>& model_classes);

// ParseClassMap of the file 'path'.
Result<ClassMap> LoadClassMap(const std::filesystem::path& path,
                              const std::vector<std::string>& model_classes);

// 'candidates' (class ids of the model) with the dropped classes' candidates removed and the
// others given their mapped class id. The detector's class-wise NMS runs after this, so that
// boxes of model classes mapped to one class (tv and laptop: computer) suppress each other.
std::vector<Candidate> MapCandidates(std::vector<Candidate> candidates, const ClassMap& map);

}  // namespace semchain::detection
