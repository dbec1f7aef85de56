#pragma once

#include <CLI/CLI.hpp>

// Options that name a file semchain ships (a world, a SLAM configuration, the detector) accept
// it by its path in the source tree from any folder, installed or not.
namespace semchain::app {

// The detector `detect` runs when --model is not given.
inline constexpr char kDefaultDetector[] = "models/detector.onnx";

// A CLI11 transform: the option's value as given when it exists (absolute, or relative to the
// current folder), else its copy among the shipped files ('worlds/office_floor.yaml' →
// PREFIX/share/semchain/worlds/office_floor.yaml; core/data_path.h), else as given.
CLI::Validator ShippedFile();

}  // namespace semchain::app
