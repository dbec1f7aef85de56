#include "semantic/keyframes.h"

#include <cmath>
#include <cstdint>
#include <limits>
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

// 'node' as an int; false when it is no integer or does not fit (get<int> would wrap it).
bool ToInt(const json& node, int* value) {
  if (node.is_number_unsigned()) {
    if (node.get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<int>::max())) {
      return false;
    }
  } else if (!node.is_number_integer() ||
             node.get<std::int64_t>() < std::numeric_limits<int>::min() ||
             node.get<std::int64_t>() > std::numeric_limits<int>::max()) {
    return false;
  }
  *value = node.get<int>();
  return true;
}

// The int at 'key' of 'object', 'fallback' when absent (json::value() would throw on a string).
bool OptionalInt(const json& object, const char* key, int fallback, int* value) {
  const auto it = object.find(key);
  if (it == object.end()) {
    *value = fallback;
    return true;
  }
  return ToInt(*it, value);
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
  } catch (const json::exception&) {  // parse_error, or out_of_range for a number like 1e999
    return Status::Error(source + ": not valid JSON");
  }
  int version = 0;
  if (!root.is_object() || !OptionalInt(root, "version", 0, &version) || version != 1) {
    return error("version", "expected 1");
  }
  if (!root.contains("run") || !root["run"].is_string()) return error("run", "expected a path");
  if (!root.contains("keyframes") || !root["keyframes"].is_array()) {
    return error("keyframes", "expected a list");
  }
  KeyframeDatabase database;
  database.run = root["run"].get<std::string>();
  // A relative run is the map folder's own (the ROS node stores the keyframes' images there), so
  // the folder can be moved or copied to a robot as a whole.
  if (!database.run.empty() && std::filesystem::path(database.run).is_relative()) {
    database.run = (path.parent_path() / database.run).lexically_normal().string();
  }
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
      KeyframeObject object;
      if (!o.is_object() || !o.contains("id") || !ToInt(o["id"], &object.id) ||
          !o.contains("class") || !o["class"].is_string() || !o.contains("box") ||
          !FiniteNumbers(o["box"], 4) || !o.contains("depth_m") || !o["depth_m"].is_number()) {
        return error(object_where, "expected id, class, box (4 numbers) and depth_m");
      }
      object.class_name = o["class"].get<std::string>();
      for (int k = 0; k < 4; ++k) object.box[k] = o["box"][k].get<double>();
      object.depth_m = o["depth_m"].get<double>();
      if (!OptionalInt(o, "upstream", -1, &object.upstream) ||
          !OptionalInt(o, "downstream", -1, &object.downstream)) {
        return error(object_where, "upstream and downstream must be integers");
      }
      keyframe.objects.push_back(object);
    }
    database.keyframes.push_back(std::move(keyframe));
  }
  return database;
}

}  // namespace semchain::semantic
