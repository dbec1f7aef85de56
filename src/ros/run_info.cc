#include "ros/run_info.h"

#include <cmath>
#include <nlohmann/json.hpp>

namespace semchain::ros1 {
namespace {

using nlohmann::json;

constexpr char kFormat[] = "semchain-run-info";
constexpr int kVersion = 1;

Result<double> PositiveNumber(const json& object, const char* key, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end() || !it->is_number() || !(it->get<double>() > 0.0) ||
      !std::isfinite(it->get<double>())) {
    return Status::Error(where + ": camera." + key + ": expected a positive number");
  }
  return it->get<double>();
}

Result<CameraExtras> ParseCamera(const json& camera, const std::string& where) {
  if (!camera.is_object()) return Status::Error(where + ": camera: expected an object");
  CameraExtras extras;
  for (auto [key, field] :
       {std::pair{"max_range", &extras.max_range}, std::pair{"depth_scale", &extras.depth_scale},
        std::pair{"frame_rate_hz", &extras.frame_rate_hz}}) {
    Result<double> value = PositiveNumber(camera, key, where);
    if (!value.ok()) return value.status();
    *field = *value;
  }
  return extras;
}

Result<RunInfo> ParseRunInfoJson(const json& root, const std::string& where) {
  if (!root.is_object() || root.value("format", "") != kFormat) {
    return Status::Error(where + ": not a semchain run info (no \"format\": \"" + kFormat + "\")");
  }
  const auto version = root.find("version");
  if (version == root.end() || *version != kVersion) {
    return Status::Error(where + ": run info version " +
                         (version == root.end() ? "missing" : version->dump()) +
                         ", this semchain reads version " + std::to_string(kVersion));
  }
  RunInfo info;
  const auto offset = root.find("stamp_offset_s");
  if (offset == root.end() || !offset->is_number_integer()) {
    return Status::Error(where + ": stamp_offset_s: expected whole seconds");
  }
  info.stamp_offset_seconds = offset->get<std::int64_t>();
  if (root.contains("camera")) {
    Result<CameraExtras> camera = ParseCamera(root.at("camera"), where);
    if (!camera.ok()) return camera.status();
    info.camera = *camera;
  }
  if (root.contains("world_yaml")) {
    if (!root.at("world_yaml").is_string()) {
      return Status::Error(where + ": world_yaml: expected text");
    }
    info.world_yaml = root.at("world_yaml").get<std::string>();
  }
  return info;
}

}  // namespace

std::string FormatRunInfo(const RunInfo& info) {
  nlohmann::ordered_json root = {
      {"format", kFormat}, {"version", kVersion}, {"stamp_offset_s", info.stamp_offset_seconds}};
  if (info.camera) {
    root["camera"] = {{"max_range", info.camera->max_range},
                      {"depth_scale", info.camera->depth_scale},
                      {"frame_rate_hz", info.camera->frame_rate_hz}};
  }
  if (info.world_yaml) root["world_yaml"] = *info.world_yaml;
  return root.dump();
}

Result<RunInfo> ParseRunInfo(const std::string& text, const std::string& where) {
  try {
    return ParseRunInfoJson(json::parse(text), where);
  } catch (const json::exception& error) {
    return Status::Error(where + ": malformed run info: " + error.what());
  }
}

}  // namespace semchain::ros1
