#pragma once

#include <filesystem>

#include "core/status.h"
#include "io/yaml_reader.h"
#include "mapping/slam_pipeline.h"

// Reads the SLAM options from YAML (config/slam.yaml documents every key). Keys left out keep
// the value already in the struct (the in-class defaults); unknown keys are errors naming file,
// line and key path, and the result is validated.
namespace semchain::mapping {

Status ReadSlamOptions(const yaml::Node& root, SlamOptions* options);
Status LoadSlamOptions(const std::filesystem::path& path, SlamOptions* options);

// Applies a named variant of seed 003's improvements on top of 'options': "plain" (GMapping:
// no annealing, low-variance resampling), "annealing", "genetic" or "both".
Status ApplyVariant(const std::string& variant, SlamOptions* options);

}  // namespace semchain::mapping
