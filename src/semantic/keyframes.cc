#include "semantic/keyframes.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"

namespace semchain::semantic {
namespace {

using nlohmann::json;

bool FiniteNumbers(const json& node, std::size_t count) {
  if (!node.is_array() || node.size() != count) return false;
  for (const json& value : node) {
    if (!value.is_number() || !std::isfinite(value.get<double>())) return false;
  }
  return true;
}

}  // namespace

Status WriteKeyframes(const std::filesystem::path& path, const KeyframeDatabase& database) {
  json keyframes = json::array();
  for (const Keyframe& keyframe : database.keyframes) {
    json objects = json::array();
    for (const KeyframeObject& object : keyframe.objects) {
      objects.push_back({{"id", object.id},
                         {"class", object.class_name},
                         {"box", {object.box[0], object.box[1], object.box[2], object.box[3]}},
                         {"depth_m", object.depth_m},
                         {"upstream", object.upstream},
                         {"downstream", object.downstream}});
    }
    keyframes.push_back({{"frame", keyframe.frame},
                         {"stamp", keyframe.stamp},
                         {"pose", {keyframe.pose.x, keyframe.pose.y, keyframe.pose.theta}},
                         {"objects", objects}});
  }
  const json root = {{"version", 1}, {"run", database.run}, {"keyframes", keyframes}};
  return WriteFileAtomically(path, root.dump(1) + "\n");
}

Result<KeyframeDatabase> ReadKeyframes(const std::filesystem::path& path) {
  Result<std::string> text = ReadFile(path);
  if (!text.ok()) return text.status();
  const std::string source = path.string();
  const auto error = [&](const std::string& where, const std::string& what) {
    return Status::Error(source + ": " + where + ": " + what);
  };
  json root;
  try {
    root = json::parse(*text);
  } catch (const json::parse_error&) {
    return Status::Error(source + ": not valid JSON");
  }
  if (!root.is_object() || root.value("version", 0) != 1) return error("version", "expected 1");
  if (!root.contains("run") || !root["run"].is_string()) return error("run", "expected a path");
  if (!root.contains("keyframes") || !root["keyframes"].is_array()) {
    return error("keyframes", "expected a list");
  }
  KeyframeDatabase database;
  database.run = root["run"].get<std::string>();
  const json& list = root["keyframes"];
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = "keyframes[" + std::to_string(i) + "]";
    const json& node = list[i];
    if (!node.is_object()) return error(where, "expected an object");
    Keyframe keyframe;
    if (!node.contains("frame") || !node["frame"].is_string())
      return error(where + ".frame", "missing");
    keyframe.frame = node["frame"].get<std::string>();
    if (!node.contains("stamp") || !node["stamp"].is_number())
      return error(where + ".stamp", "expected a number");
    keyframe.stamp = node["stamp"].get<double>();
    if (!node.contains("pose") || !FiniteNumbers(node["pose"], 3)) {
      return error(where + ".pose", "expected 3 numbers");
    }
    keyframe.pose = Pose2(node["pose"][0].get<double>(), node["pose"][1].get<double>(),
                          node["pose"][2].get<double>());
    if (!node.contains("objects") || !node["objects"].is_array()) {
      return error(where + ".objects", "expected a list");
    }
    for (std::size_t j = 0; j < node["objects"].size(); ++j) {
      const std::string object_where = where + ".objects[" + std::to_string(j) + "]";
      const json& o = node["objects"][j];
      if (!o.is_object() || !o.contains("id") || !o["id"].is_number_integer() ||
          !o.contains("class") || !o["class"].is_string() || !o.contains("box") ||
          !FiniteNumbers(o["box"], 4) || !o.contains("depth_m") || !o["depth_m"].is_number()) {
        return error(object_where, "expected id, class, box (4 numbers) and depth_m");
      }
      KeyframeObject object;
      object.id = o["id"].get<int>();
      object.class_name = o["class"].get<std::string>();
      for (int k = 0; k < 4; ++k) object.box[k] = o["box"][k].get<double>();
      object.depth_m = o["depth_m"].get<double>();
      object.upstream = o.value("upstream", -1);
      object.downstream = o.value("downstream", -1);
      keyframe.objects.push_back(object);
    }
    database.keyframes.push_back(std::move(keyframe));
  }
  return database;
}

}  // namespace semchain::semantic
