#include "io/detections_io.h"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/atomic_file.h"

namespace semchain {
namespace {

using nlohmann::json;

// Validates one JSON line field by field; errors are "<where>: <field>: <what>".
class LineReader {
 public:
  explicit LineReader(std::string where) : where_(std::move(where)) {}

  Status Error(const std::string& field, const std::string& message) const {
    return Status::Error(where_ + ": " + field + ": " + message);
  }

  // The member 'key' of object 'object' (whose path is 'path'), or an error when missing.
  Result<const json*> Member(const json& object, const std::string& path,
                             const std::string& key) const {
    const std::string field = path.empty() ? key : path + "." + key;
    const auto it = object.find(key);
    if (it == object.end()) return Error(field, "missing");
    return &*it;
  }

  Status Number(const json& object, const std::string& path, const std::string& key,
                double* value) const {
    Result<const json*> member = Member(object, path, key);
    if (!member.ok()) return member.status();
    return ToNumber(**member, path.empty() ? key : path + "." + key, value);
  }

  Status ToNumber(const json& node, const std::string& field, double* value) const {
    if (!node.is_number()) return Error(field, "expected a number, got " + node.dump());
    *value = node.get<double>();
    if (!std::isfinite(*value)) return Error(field, "not finite");
    return Status::Ok();
  }

  Status String(const json& object, const std::string& path, const std::string& key,
                std::string* value) const {
    Result<const json*> member = Member(object, path, key);
    if (!member.ok()) return member.status();
    if (!(*member)->is_string()) {
      return Error(path.empty() ? key : path + "." + key,
                   "expected a string, got " + (*member)->dump());
    }
    *value = (*member)->get<std::string>();
    return Status::Ok();
  }

  Status Detection(const json& node, const std::string& path, semchain::Detection* d) const;
  Result<FrameDetections> Frame(const std::string& line) const;

 private:
  std::string where_;
};

Status LineReader::Detection(const json& node, const std::string& path,
                             semchain::Detection* d) const {
  if (!node.is_object()) return Error(path, "expected an object, got " + node.dump());
  SEMCHAIN_RETURN_IF_ERROR(String(node, path, "class", &d->class_name));
  Result<const json*> id = Member(node, path, "class_id");
  if (!id.ok()) return id.status();
  const json& id_node = **id;
  if (!id_node.is_number_integer() || id_node.get<std::int64_t>() < -1 ||
      id_node.get<std::int64_t>() > std::numeric_limits<int>::max()) {
    return Error(path + ".class_id", "expected an integer >= -1, got " + id_node.dump());
  }
  d->class_id = id_node.get<int>();
  SEMCHAIN_RETURN_IF_ERROR(Number(node, path, "score", &d->score));
  if (d->score < 0.0 || d->score > 1.0) return Error(path + ".score", "not in [0, 1]");
  Result<const json*> box = Member(node, path, "box");
  if (!box.ok()) return box.status();
  if (!(*box)->is_array() || (*box)->size() != 4) {
    return Error(path + ".box", "expected 4 numbers [x1, y1, x2, y2], got " + (*box)->dump());
  }
  for (std::size_t i = 0; i < 4; ++i) {
    SEMCHAIN_RETURN_IF_ERROR(ToNumber((**box)[i], path + ".box", &d->box[i]));
  }
  if (d->box[0] > d->box[2] || d->box[1] > d->box[3]) {
    return Error(path + ".box", "expected x1 <= x2 and y1 <= y2, got " + (*box)->dump());
  }
  SEMCHAIN_RETURN_IF_ERROR(Number(node, path, "depth_m", &d->depth_m));
  if (d->depth_m < 0.0) return Error(path + ".depth_m", "negative");
  return Status::Ok();
}

Result<FrameDetections> LineReader::Frame(const std::string& line) const {
  json root;
  try {
    root = json::parse(line);
  } catch (const json::exception& error) {
    return Status::Error(where_ + ": invalid JSON: " + error.what());
  }
  if (!root.is_object()) return Status::Error(where_ + ": expected a JSON object per line");
  FrameDetections frame;
  SEMCHAIN_RETURN_IF_ERROR(String(root, "", "frame", &frame.frame));
  SEMCHAIN_RETURN_IF_ERROR(Number(root, "", "stamp", &frame.stamp));
  Result<const json*> detections = Member(root, "", "detections");
  if (!detections.ok()) return detections.status();
  if (!(*detections)->is_array()) {
    return Error("detections", "expected a list, got " + (*detections)->dump());
  }
  for (std::size_t i = 0; i < (*detections)->size(); ++i) {
    semchain::Detection detection;
    const std::string path = "detections[" + std::to_string(i) + "]";
    SEMCHAIN_RETURN_IF_ERROR(Detection((**detections)[i], path, &detection));
    frame.detections.push_back(std::move(detection));
  }
  return frame;
}

// JSON has no NaN or infinity: a frame with one cannot be written faithfully.
Status CheckFinite(const FrameDetections& frame) {
  bool finite = std::isfinite(frame.stamp);
  for (const semchain::Detection& d : frame.detections) {
    finite = finite && std::isfinite(d.score) && std::isfinite(d.depth_m);
    for (const double v : d.box) finite = finite && std::isfinite(v);
  }
  if (finite) return Status::Ok();
  return Status::Error("frame '" + frame.frame + "': non-finite number");
}

std::string Trim(const std::string& text) {
  const std::size_t begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  return text.substr(begin, text.find_last_not_of(" \t\r") - begin + 1);
}

}  // namespace

Result<std::string> FormatDetectionsRecord(const FrameDetections& frame) {
  SEMCHAIN_RETURN_IF_ERROR(CheckFinite(frame));
  // ordered_json keeps the field order of DESIGN.md §5.5 in the file.
  nlohmann::ordered_json detections = nlohmann::ordered_json::array();
  for (const Detection& d : frame.detections) {
    detections.push_back({{"class", d.class_name},
                          {"class_id", d.class_id},
                          {"score", d.score},
                          {"box", {d.box[0], d.box[1], d.box[2], d.box[3]}},
                          {"depth_m", d.depth_m}});
  }
  const nlohmann::ordered_json line = {
      {"frame", frame.frame}, {"stamp", frame.stamp}, {"detections", detections}};
  return line.dump();
}

Result<FrameDetections> ParseDetectionsRecord(const std::string& line, const std::string& where) {
  return LineReader(where).Frame(line);
}

Status WriteDetectionsJsonl(const std::filesystem::path& path,
                            const std::vector<FrameDetections>& frames) {
  return WriteFileAtomically(path, [&frames, &path](std::ostream& out) {
    for (const FrameDetections& frame : frames) {
      Result<std::string> line = FormatDetectionsRecord(frame);
      if (!line.ok()) return line.status().WithContext(path.string());
      out << *line << '\n';
    }
    return Status::Ok();
  });
}

Result<std::vector<FrameDetections>> ReadDetectionsJsonl(const std::filesystem::path& path) {
  Result<std::string> contents = ReadFile(path);
  if (!contents.ok()) return contents.status();
  std::istringstream in(*contents);
  std::vector<FrameDetections> frames;
  std::string line;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    if (Trim(line).empty()) continue;
    Result<FrameDetections> frame =
        ParseDetectionsRecord(line, path.string() + ":" + std::to_string(line_number));
    if (!frame.ok()) return frame.status();
    frames.push_back(std::move(*frame));
  }
  return frames;
}

Result<std::vector<std::string>> ReadClassNames(const std::filesystem::path& path) {
  Result<std::string> contents = ReadFile(path);
  if (!contents.ok()) return contents.status();
  std::istringstream in(*contents);
  std::vector<std::string> names;
  std::set<std::string> seen;
  int blank_line = 0;  // the first blank line since the last name, 0 if none
  std::string line;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    const std::string name = Trim(line);
    if (name.empty()) {
      if (blank_line == 0) blank_line = line_number;
      continue;
    }
    const std::string where = path.string() + ":" + std::to_string(line_number);
    if (blank_line != 0) {
      return Status::Error(path.string() + ":" + std::to_string(blank_line) +
                           ": blank line before the last class name (it would shift class ids)");
    }
    if (!seen.insert(name).second) return Status::Error(where + ": class '" + name + "' repeated");
    names.push_back(name);
  }
  if (names.empty()) return Status::Error(path.string() + ": no class names");
  return names;
}

}  // namespace semchain
