#include "detection/onnx_graph_check.h"

#include <cstdint>
#include <functional>
#include <set>
#include <vector>

namespace semchain::detection {
namespace {

enum WireType : std::uint32_t { kVarint = 0, kFixed64 = 1, kLengthDelimited = 2, kFixed32 = 5 };

// One field of a message: its number and, for varint fields, the value, for length-delimited
// fields, the bytes it holds.
struct Field {
  std::uint32_t number = 0;
  std::uint32_t wire_type = 0;
  std::string_view bytes;
  std::uint64_t value = 0;
};

bool ReadVarint(std::string_view data, std::size_t* pos, std::uint64_t* value) {
  *value = 0;
  for (int shift = 0; shift < 64 && *pos < data.size(); shift += 7) {
    const auto byte = static_cast<std::uint8_t>(data[(*pos)++]);
    *value |= static_cast<std::uint64_t>(byte & 0x7f) << shift;
    if ((byte & 0x80) == 0) return true;
  }
  return false;
}

// Calls 'visit' on each field of the message 'data'; false when the bytes are not protobuf.
bool ForEachField(std::string_view data, const std::function<bool(const Field&)>& visit) {
  std::size_t pos = 0;
  while (pos < data.size()) {
    std::uint64_t key = 0, value = 0;
    if (!ReadVarint(data, &pos, &key) || (key >> 3) == 0 || (key >> 3) > 0x1fffffff) return false;
    Field field{static_cast<std::uint32_t>(key >> 3), static_cast<std::uint32_t>(key & 7), {}};
    switch (field.wire_type) {
      case kVarint:
        if (!ReadVarint(data, &pos, &value)) return false;
        field.value = value;
        break;
      case kFixed64:
      case kFixed32: {
        const std::size_t width = field.wire_type == kFixed64 ? 8 : 4;
        if (data.size() - pos < width) return false;
        pos += width;
        break;
      }
      case kLengthDelimited:
        if (!ReadVarint(data, &pos, &value) || value > data.size() - pos) return false;
        field.bytes = data.substr(pos, static_cast<std::size_t>(value));
        pos += static_cast<std::size_t>(value);
        break;
      default:  // groups (3, 4) are not used by onnx.proto, 6 and 7 do not exist
        return false;
    }
    if (!visit(field)) return false;
  }
  return true;
}

// The string field 'number' of the message 'data' (its last occurrence, as protobuf merges).
bool StringField(std::string_view data, std::uint32_t number, std::string* value) {
  return ForEachField(data, [&](const Field& field) {
    if (field.number == number && field.wire_type == kLengthDelimited) value->assign(field.bytes);
    return true;
  });
}

struct GraphNames {
  std::set<std::string> defined;  // graph inputs and initializers
  std::vector<std::string> outputs;
  std::vector<std::string_view> nodes;
};

bool CollectGraph(std::string_view graph, GraphNames* names) {
  return ForEachField(graph, [&](const Field& field) {
    if (field.wire_type != kLengthDelimited) return true;
    std::string name;
    switch (field.number) {
      case 1:
        names->nodes.push_back(field.bytes);
        return true;
      case 5:  // TensorProto.name
        if (!StringField(field.bytes, 8, &name)) return false;
        names->defined.insert(name);
        return true;
      case 11:  // ValueInfoProto.name
      case 12:
        if (!StringField(field.bytes, 1, &name)) return false;
        if (field.number == 11) {
          names->defined.insert(name);
        } else {
          names->outputs.push_back(name);
        }
        return true;
      case 15:  // SparseTensorProto.values (a TensorProto) holds the name
        return ForEachField(field.bytes, [&](const Field& values) {
          if (values.number != 1 || values.wire_type != kLengthDelimited) return true;
          if (!StringField(values.bytes, 8, &name)) return false;
          names->defined.insert(name);
          return true;
        });
      default:
        return true;
    }
  });
}

// Bytes per element of a TensorProto.DataType OpenCV can read raw; 0 for STRING and unknown.
std::size_t ElementBytes(std::uint64_t data_type) {
  switch (data_type) {
    case 2:
    case 3:
    case 9:  // UINT8, INT8, BOOL
      return 1;
    case 4:
    case 5:
    case 10:
    case 16:  // UINT16, INT16, FLOAT16, BFLOAT16
      return 2;
    case 1:
    case 6:
    case 12:  // FLOAT, INT32, UINT32
      return 4;
    case 7:
    case 11:
    case 13:
    case 14:  // INT64, DOUBLE, UINT64, COMPLEX64
      return 8;
    case 15:  // COMPLEX128
      return 16;
    default:
      return 0;
  }
}

// Counts the values of a repeated numeric field seen as 'field': a packed run (its bytes /
// 'fixed_width', or its varints when 'fixed_width' is 0) or one unpacked value.
bool CountValues(const Field& field, std::size_t fixed_width, std::uint64_t* count,
                 std::vector<std::uint64_t>* varints = nullptr) {
  if (field.wire_type != kLengthDelimited) {
    ++*count;
    return true;
  }
  if (fixed_width > 0) {
    if (field.bytes.size() % fixed_width != 0) return false;
    *count += field.bytes.size() / fixed_width;
    return true;
  }
  std::size_t pos = 0;
  while (pos < field.bytes.size()) {
    std::uint64_t value = 0;
    if (!ReadVarint(field.bytes, &pos, &value)) return false;
    if (varints != nullptr) varints->push_back(value);
    ++*count;
  }
  return true;
}

// A TensorProto whose data does not hold as many values as its dims say: OpenCV 4.6 copies
// dims' worth of bytes from whatever the file holds (a heap overflow, found by
// fuzz/onnx_model_fuzzer.cc). Empty when the tensor is sound.
std::string TensorProblem(std::string_view tensor) {
  std::vector<std::uint64_t> dims;
  std::uint64_t dim_count = 0, data_type = 0, raw_bytes = 0, floats = 0, int32s = 0, int64s = 0,
                doubles = 0, uint64s = 0, strings = 0;
  bool has_raw = false, external = false;  // external: data_location = EXTERNAL
  const bool parsed = ForEachField(tensor, [&](const Field& field) {
    switch (field.number) {
      case 1:
        if (field.wire_type != kVarint) return CountValues(field, 0, &dim_count, &dims);
        dims.push_back(field.value);
        return true;
      case 2:
        if (field.wire_type == kVarint) data_type = field.value;
        return true;
      case 4:
        return CountValues(field, 4, &floats);
      case 5:
        return CountValues(field, 0, &int32s);
      case 6:
        ++strings;
        return true;
      case 7:
        return CountValues(field, 0, &int64s);
      case 9:
        has_raw = true;
        raw_bytes = field.bytes.size();
        return true;
      case 10:
        return CountValues(field, 8, &doubles);
      case 11:
        return CountValues(field, 0, &uint64s);
      case 14:
        if (field.wire_type == kVarint) external = field.value != 0;
        return true;
      default:
        return true;
    }
  });
  if (!parsed) return "malformed";
  if (external) return "its data is in an external file (not supported)";
  std::uint64_t elements = 1;
  constexpr std::uint64_t kMaxElements = std::uint64_t{1} << 31;
  for (const std::uint64_t dim : dims) {
    if (static_cast<std::int64_t>(dim) < 0) return "a negative dimension";
    if (dim != 0 && elements > kMaxElements / dim) return "more than 2^31 elements";
    elements *= dim;
  }
  if (elements > kMaxElements) return "more than 2^31 elements";
  const std::size_t width = ElementBytes(data_type);
  if (has_raw) {
    if (width == 0) return "raw data of an unsupported element type";
    if (raw_bytes != elements * width) {
      return std::to_string(raw_bytes) + " bytes of raw data for " + std::to_string(elements) +
             " elements of " + std::to_string(width) + " bytes";
    }
    return {};
  }
  const std::uint64_t values = floats + int32s + int64s + doubles + uint64s + strings;
  if (values != elements) {
    return std::to_string(values) + " values for " + std::to_string(elements) + " elements";
  }
  return {};
}

// The integers of an AttributeProto ('i' = 3 and 'ints' = 8, packed or not) when its name is
// one of the sizes OpenCV divides by (group, strides, dilations, kernel_shape): each must be at
// least 1 (a Conv with group 0 divided by zero inside OpenCV 4.6, found by
// fuzz/onnx_model_fuzzer.cc). Empty when the attribute is sound or not one of them.
std::string AttributeProblem(std::string_view attribute) {
  std::string name;
  if (!StringField(attribute, 1, &name)) return "malformed";
  if (name != "group" && name != "strides" && name != "dilations" && name != "kernel_shape") {
    return {};
  }
  std::vector<std::uint64_t> values;
  std::uint64_t count = 0;
  if (!ForEachField(attribute, [&](const Field& field) {
        if (field.number == 3 && field.wire_type == kVarint) values.push_back(field.value);
        if (field.number != 8) return true;
        if (field.wire_type == kVarint) {
          values.push_back(field.value);
          return true;
        }
        return field.wire_type != kLengthDelimited || CountValues(field, 0, &count, &values);
      })) {
    return "malformed";
  }
  for (const std::uint64_t value : values) {
    const auto signed_value = static_cast<std::int64_t>(value);
    if (signed_value < 1 || signed_value > (std::int64_t{1} << 20)) {
      return "attribute '" + name + "' is " + std::to_string(signed_value) +
             " (must be from 1 to 2^20)";
    }
  }
  return {};
}

// A name from the file for an error message: at most 64 characters, control bytes as '?', so
// that the message stays one readable line.
std::string Printable(std::string_view name) {
  std::string text(name.substr(0, 64));
  for (char& c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  return name.size() > 64 ? text + "..." : text;
}

// The message field 'number' of 'data' (its last occurrence).
std::optional<std::string_view> MessageField(std::string_view data, std::uint32_t number) {
  std::optional<std::string_view> found;
  if (!ForEachField(data, [&](const Field& field) {
        if (field.number == number && field.wire_type == kLengthDelimited) found = field.bytes;
        return true;
      })) {
    return std::nullopt;
  }
  return found;
}

// The dimensions of a ValueInfoProto's tensor shape; -1 for a symbolic or missing value.
std::optional<std::vector<std::int64_t>> TensorDims(std::string_view value_info) {
  const std::optional<std::string_view> type = MessageField(value_info, 2);
  if (!type) return std::nullopt;
  const std::optional<std::string_view> tensor = MessageField(*type, 1);
  if (!tensor) return std::nullopt;
  const std::optional<std::string_view> shape = MessageField(*tensor, 2);
  if (!shape) return std::nullopt;
  std::vector<std::int64_t> dims;
  const bool ok = ForEachField(*shape, [&](const Field& dim) {
    if (dim.number != 1 || dim.wire_type != kLengthDelimited) return true;
    std::int64_t value = -1;  // dim_param (a symbolic size) or nothing: unknown
    // Dimension has only varint and string fields: a fixed-width one means it is not one.
    if (!ForEachField(dim.bytes, [&](const Field& part) {
          if (part.number == 1 && part.wire_type == kVarint) {
            value = static_cast<std::int64_t>(part.value);
          }
          return part.wire_type == kVarint || part.wire_type == kLengthDelimited;
        })) {
      return false;
    }
    dims.push_back(value);
    return true;
  });
  if (!ok) return std::nullopt;
  return dims;
}

}  // namespace

std::optional<std::pair<int, int>> OnnxStaticInputSize(std::string_view bytes) {
  const std::optional<std::string_view> graph = MessageField(bytes, 7);
  if (!graph) return std::nullopt;
  std::set<std::string> initializers;
  std::vector<std::string_view> inputs;
  if (!ForEachField(*graph, [&](const Field& field) {
        if (field.wire_type != kLengthDelimited) return true;
        std::string name;
        if (field.number == 5) {
          if (!StringField(field.bytes, 8, &name)) return false;
          initializers.insert(name);
        } else if (field.number == 11) {
          inputs.push_back(field.bytes);
        }
        return true;
      })) {
    return std::nullopt;
  }
  for (std::string_view input : inputs) {
    std::string name;
    if (!StringField(input, 1, &name) || initializers.count(name) > 0) continue;
    const std::optional<std::vector<std::int64_t>> dims = TensorDims(input);
    if (!dims || dims->size() != 4) return std::nullopt;
    const std::int64_t height = (*dims)[2], width = (*dims)[3];
    constexpr std::int64_t kLargest = 1 << 14;
    if (height <= 0 || width <= 0 || height > kLargest || width > kLargest) return std::nullopt;
    return std::pair<int, int>(static_cast<int>(width), static_cast<int>(height));
  }
  return std::nullopt;
}

Status CheckOnnxGraph(std::string_view bytes, const std::string& source) {
  const Status malformed = Status::Error(source + ": not an ONNX model (malformed protobuf)");
  std::string_view graph;
  bool has_graph = false;
  if (!ForEachField(bytes, [&](const Field& field) {
        if (field.number == 7 && field.wire_type == kLengthDelimited) {
          graph = field.bytes;
          has_graph = true;
        }
        return true;
      })) {
    return malformed;
  }
  if (!has_graph) return Status::Error(source + ": not an ONNX model (no graph)");
  GraphNames names;
  if (!CollectGraph(graph, &names)) return malformed;
  std::string tensor_error;
  const auto check_tensor = [&](std::string_view tensor, const std::string& where) {
    const std::string problem = TensorProblem(tensor);
    if (problem.empty()) return true;
    std::string name;
    StringField(tensor, 8, &name);
    tensor_error = source + ": ONNX " + where + " tensor '" + Printable(name) + "': " + problem;
    return false;
  };
  if (!ForEachField(graph, [&](const Field& field) {
        return field.number != 5 || field.wire_type != kLengthDelimited ||
               check_tensor(field.bytes, "initializer");
      })) {
    return tensor_error.empty() ? malformed : Status::Error(tensor_error);
  }
  for (std::size_t index = 0; index < names.nodes.size(); ++index) {
    std::vector<std::string> inputs, outputs;
    std::string op_type;
    std::vector<std::string_view> attributes;
    if (!ForEachField(names.nodes[index], [&](const Field& field) {
          if (field.wire_type != kLengthDelimited) return true;
          if (field.number == 1) inputs.emplace_back(field.bytes);
          if (field.number == 2) outputs.emplace_back(field.bytes);
          if (field.number == 4) op_type.assign(field.bytes);
          if (field.number == 5) attributes.push_back(field.bytes);
          return true;
        })) {
      return malformed;
    }
    // AttributeProto.t = 5 and .tensors = 11: a Constant's value, read like an initializer.
    const std::string where = "node " + std::to_string(index) + " attribute";
    for (std::string_view attribute : attributes) {
      const std::string problem = AttributeProblem(attribute);
      if (problem == "malformed") return malformed;
      if (!problem.empty()) {
        return Status::Error(source + ": ONNX node " + std::to_string(index) + " (" +
                             Printable(op_type) + "): " + problem);
      }
      if (!ForEachField(attribute, [&](const Field& field) {
            return (field.number != 5 && field.number != 11) ||
                   field.wire_type != kLengthDelimited || check_tensor(field.bytes, where);
          })) {
        return tensor_error.empty() ? malformed : Status::Error(tensor_error);
      }
    }
    for (const std::string& input : inputs) {
      if (!input.empty() && names.defined.count(input) == 0) {
        return Status::Error(source + ": ONNX node " + std::to_string(index) + " (" +
                             Printable(op_type) + ") reads '" + Printable(input) +
                             "', which no graph input, initializer or earlier node provides");
      }
    }
    names.defined.insert(outputs.begin(), outputs.end());
  }
  for (const std::string& output : names.outputs) {
    if (names.defined.count(output) == 0) {
      return Status::Error(source + ": ONNX graph output '" + Printable(output) +
                           "' is produced by no node");
    }
  }
  return Status::Ok();
}

}  // namespace semchain::detection
