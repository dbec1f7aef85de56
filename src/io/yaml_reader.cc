#include "io/yaml_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <set>
#include <system_error>
#include <utility>

#include "core/atomic_file.h"
#include "io/text_fields.h"

namespace semchain::yaml {
namespace {

std::string LineOf(const std::string& source, const YAML::Mark& mark) {
  if (mark.is_null()) return source;
  return source + ":" + std::to_string(mark.line + 1);  // YAML::Mark lines are 0-based
}

// Parses all of 'text' as a finite double ("1.5x", "", "nan" and "inf" fail).
bool ParseStrictDouble(const std::string& text, double* value) {
  return text::ParseDouble(text, value) && std::isfinite(*value);
}

std::string JoinKeys(const std::vector<std::string>& keys) {
  std::string joined;
  for (const std::string& key : keys) joined += (joined.empty() ? "" : ", ") + key;
  return joined;
}

}  // namespace

Node::Node() : source_(std::make_shared<const std::string>("<none>")) {}

Node::Node(YAML::Node node, std::shared_ptr<const std::string> source, std::string path,
           YAML::Mark mark)
    : node_(std::move(node)), source_(std::move(source)), path_(std::move(path)), mark_(mark) {}

Result<Node> Node::LoadFile(const std::filesystem::path& path) {
  Result<std::string> text = ReadFile(path);
  if (!text.ok()) return text.status();
  return LoadString(*text, path.string());
}

Result<Node> Node::LoadString(const std::string& text, const std::string& source_name) {
  try {
    YAML::Node root = YAML::Load(text);
    const YAML::Mark mark = root.IsDefined() && !root.IsNull() ? root.Mark() : YAML::Mark();
    return Node(root, std::make_shared<const std::string>(source_name), "", mark);
  } catch (const YAML::ParserException& error) {
    return Status::Error(LineOf(source_name, error.mark) + ": " + error.msg);
  } catch (const YAML::Exception& error) {
    return Status::Error(source_name + ": " + error.msg);
  }
}

std::size_t Node::size() const { return node_.IsMap() || node_.IsSequence() ? node_.size() : 0; }

bool Node::Has(const std::string& key) const {
  if (!node_.IsMap()) return false;
  for (const auto& entry : node_) {
    if (entry.first.IsScalar() && entry.first.Scalar() == key) return true;
  }
  return false;
}

Result<Node> Node::Get(const std::string& key) const {
  if (!node_.IsMap() && !IsNull()) return Error("expected a map, got " + Describe());
  if (node_.IsMap()) {
    for (const auto& entry : node_) {
      if (!entry.first.IsScalar() || entry.first.Scalar() != key) continue;
      // An empty value ("key:") has its mark after the key, often on the next line.
      const YAML::Mark mark = entry.second.IsNull() ? entry.first.Mark() : entry.second.Mark();
      return Node(entry.second, source_, ChildPath(key), mark);
    }
  }
  return Node(YAML::Node(), source_, ChildPath(key), mark_).Error("missing");
}

Node Node::At(std::size_t index) const {
  SEMCHAIN_CHECK(node_.IsSequence() && index < node_.size());
  const YAML::Node& self = node_;
  const YAML::Node child = self[index];
  return Node(child, source_, path_ + "[" + std::to_string(index) + "]", child.Mark());
}

std::vector<std::string> Node::Keys() const {
  std::vector<std::string> keys;
  if (!node_.IsMap()) return keys;
  for (const auto& entry : node_) {
    keys.push_back(entry.first.IsScalar() ? entry.first.Scalar() : std::string());
  }
  return keys;
}

Result<std::string> Node::ScalarText(const char* kind) const {
  if (!node_.IsScalar()) return Error(std::string("expected ") + kind + ", got " + Describe());
  return node_.Scalar();
}

Result<double> Node::AsDouble() const {
  Result<std::string> text = ScalarText("a number");
  if (!text.ok()) return text.status();
  double value = 0.0;
  if (!ParseStrictDouble(*text, &value)) return Error("'" + *text + "' is not a number");
  return value;
}

Result<int> Node::AsInt() const {
  Result<std::string> text = ScalarText("an integer");
  if (!text.ok()) return text.status();
  const std::string& s = *text;
  const std::size_t skip = !s.empty() && s[0] == '+' && s.size() > 1 && s[1] != '-' ? 1 : 0;
  int value = 0;
  const auto [ptr, error] = std::from_chars(s.data() + skip, s.data() + s.size(), value);
  if (error == std::errc::result_out_of_range) return Error("'" + s + "' is out of range");
  if (error != std::errc() || ptr != s.data() + s.size() || s.size() == skip) {
    return Error("'" + s + "' is not an integer");
  }
  return value;
}

Result<bool> Node::AsBool() const {
  Result<std::string> text = ScalarText("true or false");
  if (!text.ok()) return text.status();
  const std::string& s = *text;
  if (s == "true" || s == "True" || s == "TRUE") return true;
  if (s == "false" || s == "False" || s == "FALSE") return false;
  return Error("'" + s + "' is not a boolean (use true or false)");
}

Result<std::string> Node::AsString() const { return ScalarText("a string"); }

Result<std::vector<double>> Node::AsDoubleList(std::size_t expected_size) const {
  if (!node_.IsSequence()) return Error("expected a list of numbers, got " + Describe());
  if (expected_size != 0 && node_.size() != expected_size) {
    return Error("expected " + std::to_string(expected_size) + " numbers, got " +
                 std::to_string(node_.size()));
  }
  std::vector<double> values;
  for (std::size_t i = 0; i < node_.size(); ++i) {
    Result<double> value = At(i).AsDouble();
    if (!value.ok()) return value.status();
    values.push_back(*value);
  }
  return values;
}

Status Node::CheckKeys(const std::vector<std::string>& allowed) const {
  if (IsNull()) return Status::Ok();
  if (!node_.IsMap()) return Error("expected a map, got " + Describe());
  std::set<std::string> seen;
  for (const auto& entry : node_) {
    const YAML::Node& key = entry.first;
    const Node key_node(key, source_, path_, key.Mark());
    if (!key.IsScalar()) return key_node.Error("map keys must be plain names");
    const std::string name = key.Scalar();
    const Node named(key, source_, ChildPath(name), key.Mark());
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
      return named.Error("unknown key (allowed: " + JoinKeys(allowed) + ")");
    }
    if (!seen.insert(name).second) return named.Error("duplicate key");
  }
  return Status::Ok();
}

std::string Node::Where() const {
  const std::string location = LineOf(*source_, mark_);
  return path_.empty() ? location : location + ": " + path_;
}

Status Node::Error(const std::string& message) const {
  return Status::Error(Where() + ": " + message);
}

std::string Node::ChildPath(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

std::string Node::Describe() const {
  if (IsNull()) return "nothing";
  if (node_.IsMap()) return "a map";
  if (node_.IsSequence()) return "a sequence";
  return "'" + node_.Scalar() + "'";
}

namespace {

// Reads 'key' of 'map' into '*value' with 'convert' when present.
template <typename T, typename Convert>
Status ReadOptionalWith(const Node& map, const std::string& key, T* value, Convert convert) {
  if (!map.IsMap() && !map.IsNull()) return map.Error("expected a map");
  if (!map.Has(key)) return Status::Ok();
  Result<Node> child = map.Get(key);
  if (!child.ok()) return child.status();
  auto converted = convert(*child);
  if (!converted.ok()) return converted.status();
  *value = std::move(*converted);
  return Status::Ok();
}

}  // namespace

Status ReadOptional(const Node& map, const std::string& key, double* value) {
  return ReadOptionalWith(map, key, value, [](const Node& n) { return n.AsDouble(); });
}
Status ReadOptional(const Node& map, const std::string& key, int* value) {
  return ReadOptionalWith(map, key, value, [](const Node& n) { return n.AsInt(); });
}
Status ReadOptional(const Node& map, const std::string& key, bool* value) {
  return ReadOptionalWith(map, key, value, [](const Node& n) { return n.AsBool(); });
}
Status ReadOptional(const Node& map, const std::string& key, std::string* value) {
  return ReadOptionalWith(map, key, value, [](const Node& n) { return n.AsString(); });
}
Status ReadOptional(const Node& map, const std::string& key, std::vector<double>* value) {
  return ReadOptionalWith(map, key, value, [](const Node& n) { return n.AsDoubleList(); });
}

}  // namespace semchain::yaml
