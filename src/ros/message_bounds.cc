#include "ros/message_bounds.h"

#include <algorithm>
#include <charconv>
#include <limits>
#include <map>
#include <optional>
#include <string_view>

namespace semchain::ros1 {
namespace {

constexpr std::uint64_t kSaturated = std::numeric_limits<std::uint64_t>::max();
// Deeper nesting is an error: it bounds the recursion of ComputeSizes and CheckType, for a
// definition read from a bag. ROS's own types nest less than 10 deep.
constexpr int kMaxDepth = 64;

std::uint64_t SaturatingAdd(std::uint64_t a, std::uint64_t b) {
  return a > kSaturated - b ? kSaturated : a + b;
}
std::uint64_t SaturatingMul(std::uint64_t a, std::uint64_t b) {
  return a != 0 && b > kSaturated / a ? kSaturated : a * b;
}

// The size of a primitive type, 0 for a string or message type.
std::uint64_t PrimitiveSize(std::string_view type) {
  static const std::map<std::string_view, std::uint64_t> kSizes = {
      {"bool", 1},  {"int8", 1},   {"uint8", 1},   {"byte", 1},   {"char", 1},
      {"int16", 2}, {"uint16", 2}, {"int32", 4},   {"uint32", 4}, {"float32", 4},
      {"int64", 8}, {"uint64", 8}, {"float64", 8}, {"time", 8},   {"duration", 8}};
  const auto it = kSizes.find(type);
  return it == kSizes.end() ? 0 : it->second;
}

std::string_view Trim(std::string_view text) {
  const std::size_t begin = text.find_first_not_of(" \t\r");
  if (begin == std::string_view::npos) return {};
  return text.substr(begin, text.find_last_not_of(" \t\r") - begin + 1);
}

std::string Bytes(std::uint64_t count) {
  return std::to_string(count) + (count == 1 ? " byte" : " bytes");
}

// One field line of a definition: "float64[9] K  # comment" gives {"float64[9]", "K"}.
struct FieldLine {
  std::string_view type;
  std::string_view name;
};

// Nothing for a blank line, a comment or a constant ("uint8 A=1", "string S=a#b").
Result<std::optional<FieldLine>> ParseLine(std::string_view line) {
  const std::size_t end = line.find_first_of("#=");
  if (end != std::string_view::npos && line[end] == '=') return std::optional<FieldLine>();
  line = Trim(line.substr(0, end));
  if (line.empty()) return std::optional<FieldLine>();
  const std::size_t space = line.find_first_of(" \t");
  if (space == std::string_view::npos) return Status::Error("no field name");
  const FieldLine field{line.substr(0, space), Trim(line.substr(space))};
  if (field.name.find_first_of(" \t") != std::string_view::npos) {
    return Status::Error("more than a type and a name");
  }
  return std::optional<FieldLine>(field);
}

struct Section {
  std::string type;
  std::vector<std::string_view> lines;
};

// The main type's lines, then one section per "MSG: pkg/Type" line. The lines of '=' before
// each "MSG:" line carry nothing more.
std::vector<Section> SplitSections(const std::string& type, std::string_view definition) {
  std::vector<Section> sections = {{type, {}}};
  while (!definition.empty()) {
    const std::size_t end = definition.find('\n');
    const std::string_view line = Trim(definition.substr(0, end));
    definition = end == std::string_view::npos ? std::string_view() : definition.substr(end + 1);
    if (line.starts_with("MSG:")) {
      sections.push_back({std::string(Trim(line.substr(4))), {}});
    } else if (line.find_first_not_of('=') != std::string_view::npos) {
      sections.back().lines.push_back(line);
    }
  }
  return sections;
}

}  // namespace

class MessageLayout::Reader {
 public:
  Reader(const std::uint8_t* bytes, std::size_t size) : bytes_(bytes), left_(size) {}
  std::uint64_t left() const { return left_; }
  bool ReadUint32(std::uint64_t* value) {
    if (left_ < 4) return false;
    // Little-endian, as roscpp writes it on the machines ROS runs on.
    *value = std::uint64_t{bytes_[0]} | std::uint64_t{bytes_[1]} << 8 |
             std::uint64_t{bytes_[2]} << 16 | std::uint64_t{bytes_[3]} << 24;
    Skip(4);
    return true;
  }
  void Skip(std::uint64_t count) {
    SEMCHAIN_CHECK(count <= left_);
    bytes_ += count;
    left_ -= count;
  }

 private:
  const std::uint8_t* bytes_;
  std::uint64_t left_;
};

Result<MessageLayout> MessageLayout::Parse(const std::string& type, const std::string& definition) {
  const std::vector<Section> sections = SplitSections(type, definition);
  MessageLayout layout;
  std::map<std::string, std::size_t, std::less<>> index;
  for (const Section& section : sections) {
    // A repeated section is the same type again; the first one wins.
    if (index.emplace(section.type, layout.types_.size()).second) {
      layout.types_.push_back({section.type, {}});
    }
  }
  for (const Section& section : sections) {
    Type& message = layout.types_[index.at(section.type)];
    if (!message.fields.empty()) continue;
    const std::string package = section.type.substr(0, section.type.find('/'));
    for (const std::string_view line : section.lines) {
      const auto error = [&](const std::string& what) {
        return Status::Error(section.type + " definition: line '" + std::string(line) +
                             "': " + what);
      };
      const Result<std::optional<FieldLine>> parsed = ParseLine(line);
      if (!parsed.ok()) return error(parsed.status().message());
      if (!parsed->has_value()) continue;
      const FieldLine& line_field = **parsed;
      Field field{.name = std::string(line_field.name)};

      std::string_view base = line_field.type;
      if (const std::size_t bracket = base.find('['); bracket != std::string_view::npos) {
        const std::string_view count = base.substr(bracket + 1);
        base = base.substr(0, bracket);
        if (!count.ends_with(']')) return error("bad array type");
        if (count.size() == 1) {
          field.array = Array::kVariable;
        } else {
          field.array = Array::kFixed;
          const char* last = count.data() + count.size() - 1;
          const auto [end, code] = std::from_chars(count.data(), last, field.fixed_count);
          if (code != std::errc() || end != last) return error("bad array type");
        }
      }
      if (base.empty()) return error("no type");

      if (const std::uint64_t size = PrimitiveSize(base); size != 0) {
        field.primitive_size = size;
      } else if (base == "string") {
        field.kind = Kind::kString;
      } else {
        const std::string name = base == "Header" ? "std_msgs/Header"
                                 : base.find('/') != std::string_view::npos
                                     ? std::string(base)
                                     : package + "/" + std::string(base);
        const auto it = index.find(name);
        if (it == index.end()) return error("unknown type " + name);
        field.kind = Kind::kMessage;
        field.type = it->second;
      }
      message.fields.push_back(std::move(field));
    }
  }
  std::vector<int> state(layout.types_.size(), 0);
  SEMCHAIN_RETURN_IF_ERROR(layout.ComputeSizes(0, state, 0));
  return layout;
}

MessageLayout::Size MessageLayout::ElementSize(const Field& field) const {
  switch (field.kind) {
    case Kind::kPrimitive:
      return {field.primitive_size, true};
    case Kind::kString:
      return {4, false};
    case Kind::kMessage:
      return {types_[field.type].min_size, types_[field.type].fixed};
  }
  return {};
}

// 'state' per type: 0 not seen, 1 being sized (so met again it contains itself), 2 sized.
Status MessageLayout::ComputeSizes(std::size_t index, std::vector<int>& state, int depth) {
  Type& type = types_[index];
  if (state[index] == 2) return Status::Ok();
  if (state[index] == 1) return Status::Error(type.name + " definition: contains itself");
  if (depth >= kMaxDepth) return Status::Error(type.name + " definition: nested too deep");
  state[index] = 1;
  for (const Field& field : type.fields) {
    if (field.kind == Kind::kMessage) {
      SEMCHAIN_RETURN_IF_ERROR(ComputeSizes(field.type, state, depth + 1));
      type.height = std::max(type.height, types_[field.type].height + 1);
    }
    const Size element = ElementSize(field);
    switch (field.array) {
      case Array::kNone:
        type.min_size = SaturatingAdd(type.min_size, element.min);
        type.fixed = type.fixed && element.fixed;
        break;
      case Array::kFixed:
        type.min_size = SaturatingAdd(type.min_size, SaturatingMul(element.min, field.fixed_count));
        type.fixed = type.fixed && (element.fixed || field.fixed_count == 0);
        break;
      case Array::kVariable:
        type.min_size = SaturatingAdd(type.min_size, 4);
        type.fixed = false;
        break;
    }
  }
  // 'depth' alone misses a deep type met again at a lesser depth after it was sized.
  if (type.height > kMaxDepth) return Status::Error(type.name + " definition: nested too deep");
  state[index] = 2;
  return Status::Ok();
}

Status MessageLayout::Check(const std::uint8_t* bytes, std::size_t size) const {
  Reader reader(bytes, size);
  const Status status = CheckType(0, reader);
  if (!status.ok()) return Status::Error("field " + status.message().substr(1));
  if (reader.left() != 0) {
    return Status::Error(Bytes(reader.left()) + " left over after the " + type() + " message");
  }
  return Status::Ok();
}

Status MessageLayout::CheckType(std::size_t index, Reader& reader) const {
  const Type& type = types_[index];
  if (type.fixed && type.min_size <= reader.left()) {
    reader.Skip(type.min_size);
    return Status::Ok();
  }
  for (const Field& field : type.fields) {
    const Status status = CheckField(field, reader);
    if (!status.ok()) return Status::Error("." + field.name + status.message());
  }
  return Status::Ok();
}

Status MessageLayout::CheckField(const Field& field, Reader& reader) const {
  if (field.array == Array::kNone) return CheckElement(field, reader);
  std::uint64_t count = field.fixed_count;
  if (field.array == Array::kVariable && !reader.ReadUint32(&count)) {
    return Status::Error(": 4-byte element count, " + Bytes(reader.left()) + " left");
  }
  const Size element = ElementSize(field);
  // roscpp resizes a variable array to 'count' even when its elements take no bytes (a type
  // without fields), so such a count must not exceed the bytes left either.
  const std::uint64_t least =
      field.array == Array::kVariable ? std::max<std::uint64_t>(element.min, 1) : element.min;
  if (least != 0 && count > reader.left() / least) {
    return Status::Error(": " + std::to_string(count) + " elements of " +
                         (element.fixed ? "" : "at least ") + Bytes(element.min) + ", " +
                         Bytes(reader.left()) + " left");
  }
  if (element.fixed) {
    reader.Skip(count * element.min);  // no overflow: it is at most reader.left()
    return Status::Ok();
  }
  // Each element of a variable-size type takes at least 4 bytes (a length or count), so the
  // check above bounds this loop by the bytes.
  for (std::uint64_t i = 0; i < count; ++i) {
    const Status status = CheckElement(field, reader);
    if (!status.ok()) return Status::Error("[" + std::to_string(i) + "]" + status.message());
  }
  return Status::Ok();
}

Status MessageLayout::CheckElement(const Field& field, Reader& reader) const {
  switch (field.kind) {
    case Kind::kPrimitive:
      if (field.primitive_size > reader.left()) {
        return Status::Error(": " + Bytes(field.primitive_size) + ", " + Bytes(reader.left()) +
                             " left");
      }
      reader.Skip(field.primitive_size);
      return Status::Ok();
    case Kind::kString: {
      std::uint64_t length = 0;
      if (!reader.ReadUint32(&length)) {
        return Status::Error(": 4-byte string length, " + Bytes(reader.left()) + " left");
      }
      if (length > reader.left()) {
        return Status::Error(": string of " + Bytes(length) + ", " + Bytes(reader.left()) +
                             " left");
      }
      reader.Skip(length);
      return Status::Ok();
    }
    case Kind::kMessage:
      return CheckType(field.type, reader);
  }
  return Status::Ok();
}

}  // namespace semchain::ros1
