#include "detection/onnx_rewrite.h"

#include <onnx/shape_inference/implementation.h>

#include <cstdint>
#include <cstring>
#include <opencv2/core.hpp>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace semchain::detection {
namespace {

using onnx::TensorProto;

// The element count its dims give; -1 for a negative dimension.
std::int64_t ElementCount(const TensorProto& tensor) {
  std::int64_t count = 1;
  for (const std::int64_t dim : tensor.dims()) {
    if (dim < 0) return -1;
    count *= dim;
  }
  return count;
}

// Converts a FLOAT16 tensor to FLOAT in place (raw_data or the int32_data ONNX stores halves
// in); false, leaving it as it is, when it is not FLOAT16 or its data does not fit its dims.
bool ConvertTensor(TensorProto* tensor) {
  if (tensor->data_type() != TensorProto::FLOAT16) return false;
  const std::int64_t count = ElementCount(*tensor);
  if (count < 0) return false;
  std::vector<std::uint16_t> halves(static_cast<std::size_t>(count));
  if (tensor->has_raw_data()) {
    if (tensor->raw_data().size() != halves.size() * sizeof(std::uint16_t)) return false;
    std::memcpy(halves.data(), tensor->raw_data().data(), tensor->raw_data().size());
  } else {
    if (tensor->int32_data_size() != count) return false;
    for (int i = 0; i < tensor->int32_data_size(); ++i) {
      halves[static_cast<std::size_t>(i)] = static_cast<std::uint16_t>(tensor->int32_data(i));
    }
  }
  std::vector<float> floats(halves.size());
  if (!halves.empty()) {
    const cv::Mat half(1, static_cast<int>(halves.size()), CV_16F, halves.data());
    cv::Mat single(1, static_cast<int>(floats.size()), CV_32F, floats.data());
    half.convertTo(single, CV_32F);  // writes into 'floats' (same size and type)
  }
  tensor->clear_int32_data();
  tensor->set_raw_data(floats.data(), floats.size() * sizeof(float));
  tensor->set_data_type(TensorProto::FLOAT);
  return true;
}

void ConvertValueInfo(onnx::ValueInfoProto* value) {
  if (value->type().has_tensor_type() &&
      value->type().tensor_type().elem_type() == TensorProto::FLOAT16) {
    value->mutable_type()->mutable_tensor_type()->set_elem_type(TensorProto::FLOAT);
  }
}

onnx::AttributeProto* FindAttribute(onnx::NodeProto* node, const std::string& name) {
  for (onnx::AttributeProto& attribute : *node->mutable_attribute()) {
    if (attribute.name() == name) return &attribute;
  }
  return nullptr;
}

// The element type of every tensor whose type the graph states (inputs, outputs, value_info,
// initializers, Constant and Cast outputs).
std::unordered_map<std::string, int> StatedTypes(const onnx::GraphProto& graph) {
  std::unordered_map<std::string, int> types;
  for (const auto* values : {&graph.input(), &graph.output(), &graph.value_info()}) {
    for (const onnx::ValueInfoProto& value : *values) {
      if (value.type().has_tensor_type())
        types[value.name()] = value.type().tensor_type().elem_type();
    }
  }
  for (const TensorProto& tensor : graph.initializer()) types[tensor.name()] = tensor.data_type();
  for (const onnx::NodeProto& node : graph.node()) {
    if (node.output_size() == 0) continue;
    for (const onnx::AttributeProto& attribute : node.attribute()) {
      if (node.op_type() == "Constant" && attribute.name() == "value") {
        types[node.output(0)] = attribute.t().data_type();
      }
      if (node.op_type() == "Cast" && attribute.name() == "to") {
        types[node.output(0)] = static_cast<int>(attribute.i());
      }
    }
  }
  return types;
}

bool CastsToFloat(const onnx::NodeProto& node) {
  if (node.op_type() != "Cast" || node.input_size() != 1 || node.output_size() != 1) return false;
  for (const onnx::AttributeProto& attribute : node.attribute()) {
    if (attribute.name() == "to") return attribute.i() == TensorProto::FLOAT;
  }
  return false;
}

// Removes the Casts to FLOAT of FLOAT tensors; their readers read the Cast's input instead. A
// Cast whose output is a graph output stays (the output keeps its name).
void BypassRedundantCasts(onnx::ModelProto* model) {
  onnx::GraphProto* graph = model->mutable_graph();
  std::unordered_map<std::string, int> types = StatedTypes(*graph);
  bool unknown = false;
  for (const onnx::NodeProto& node : graph->node()) {
    unknown = unknown || (CastsToFloat(node) && types.count(node.input(0)) == 0);
  }
  if (unknown) {
    // onnx's shape inference on a copy: the model itself stays as it is. Its errors (a graph it
    // cannot type) only leave those Casts in place.
    onnx::ModelProto typed = *model;
    try {
      onnx::shape_inference::InferShapes(typed);
      for (const onnx::ValueInfoProto& value : typed.graph().value_info()) {
        if (value.type().has_tensor_type()) {
          types.emplace(value.name(), value.type().tensor_type().elem_type());
        }
      }
    } catch (const std::exception&) {
    }
  }
  std::unordered_map<std::string, std::string> renamed;  // a removed Cast's output -> its input
  std::unordered_set<std::string> graph_outputs;
  for (const onnx::ValueInfoProto& output : graph->output()) graph_outputs.insert(output.name());
  google::protobuf::RepeatedPtrField<onnx::NodeProto> kept;
  for (onnx::NodeProto& node : *graph->mutable_node()) {
    for (std::string& input : *node.mutable_input()) {
      const auto it = renamed.find(input);
      if (it != renamed.end()) input = it->second;
    }
    const auto type = CastsToFloat(node) ? types.find(node.input(0)) : types.end();
    if (type != types.end() && type->second == TensorProto::FLOAT &&
        graph_outputs.count(node.output(0)) == 0) {
      renamed[node.output(0)] = node.input(0);
      continue;
    }
    *kept.Add() = std::move(node);
  }
  graph->mutable_node()->Swap(&kept);
}

}  // namespace

const TensorProto* FindConstantTensor(const onnx::GraphProto& graph, const std::string& name) {
  for (const TensorProto& tensor : graph.initializer()) {
    if (tensor.name() == name) return &tensor;
  }
  for (const onnx::NodeProto& node : graph.node()) {
    if (node.op_type() != "Constant" || node.output_size() != 1 || node.output(0) != name) {
      continue;
    }
    for (const onnx::AttributeProto& attribute : node.attribute()) {
      if (attribute.name() == "value" && attribute.has_t()) return &attribute.t();
    }
  }
  return nullptr;
}

bool ReadIntegers(const TensorProto& tensor, std::vector<std::int64_t>* values) {
  const std::int64_t count = ElementCount(tensor);
  if (count < 0) return false;
  values->clear();
  if (tensor.data_type() == TensorProto::INT64) {
    if (tensor.has_raw_data()) {
      if (tensor.raw_data().size() != static_cast<std::size_t>(count) * 8) return false;
      values->resize(static_cast<std::size_t>(count));
      std::memcpy(values->data(), tensor.raw_data().data(), tensor.raw_data().size());
      return true;
    }
    if (tensor.int64_data_size() != count) return false;
    values->assign(tensor.int64_data().begin(), tensor.int64_data().end());
    return true;
  }
  if (tensor.data_type() == TensorProto::INT32) {
    if (tensor.has_raw_data()) {
      if (tensor.raw_data().size() != static_cast<std::size_t>(count) * 4) return false;
      std::vector<std::int32_t> narrow(static_cast<std::size_t>(count));
      std::memcpy(narrow.data(), tensor.raw_data().data(), tensor.raw_data().size());
      values->assign(narrow.begin(), narrow.end());
      return true;
    }
    if (tensor.int32_data_size() != count) return false;
    values->assign(tensor.int32_data().begin(), tensor.int32_data().end());
    return true;
  }
  return false;
}

int ConvertFloat16ToFloat(onnx::ModelProto* model) {
  onnx::GraphProto* graph = model->mutable_graph();
  int converted = 0;
  for (TensorProto& tensor : *graph->mutable_initializer()) converted += ConvertTensor(&tensor);
  bool casts = false;
  for (onnx::NodeProto& node : *graph->mutable_node()) {
    for (onnx::AttributeProto& attribute : *node.mutable_attribute()) {
      if (attribute.has_t()) converted += ConvertTensor(attribute.mutable_t());
      for (TensorProto& tensor : *attribute.mutable_tensors()) converted += ConvertTensor(&tensor);
    }
    onnx::AttributeProto* to = node.op_type() == "Cast" ? FindAttribute(&node, "to") : nullptr;
    if (to != nullptr && to->i() == TensorProto::FLOAT16) {
      to->set_i(TensorProto::FLOAT);
      casts = true;
    }
  }
  for (auto* values :
       {graph->mutable_input(), graph->mutable_output(), graph->mutable_value_info()}) {
    for (onnx::ValueInfoProto& value : *values) {
      const bool half = value.type().has_tensor_type() &&
                        value.type().tensor_type().elem_type() == TensorProto::FLOAT16;
      ConvertValueInfo(&value);
      converted += half;
    }
  }
  if (converted > 0 || casts) BypassRedundantCasts(model);
  return converted;
}

int MoveSplitSizesToAttributes(onnx::GraphProto* graph) {
  int changed = 0;
  for (onnx::NodeProto& node : *graph->mutable_node()) {
    if (node.op_type() != "Split" || node.input_size() != 2 || node.input(1).empty()) continue;
    if (FindAttribute(&node, "split") != nullptr) continue;
    const TensorProto* sizes = FindConstantTensor(*graph, node.input(1));
    std::vector<std::int64_t> values;
    if (sizes == nullptr || !ReadIntegers(*sizes, &values) ||
        static_cast<int>(values.size()) != node.output_size()) {
      continue;
    }
    onnx::AttributeProto* split = node.add_attribute();
    split->set_name("split");
    split->set_type(onnx::AttributeProto::INTS);
    for (const std::int64_t value : values) split->add_ints(value);
    node.mutable_input()->RemoveLast();
    ++changed;
  }
  return changed;
}

}  // namespace semchain::detection
