#include "detection/onnx_raw_head.h"

#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "detection/yolo_head.h"

namespace semchain::detection {
namespace {

// Who produces and who reads each tensor, and the shapes of the constant tensors.
class GraphIndex {
 public:
  explicit GraphIndex(const onnx::GraphProto& graph) {
    for (const onnx::TensorProto& tensor : graph.initializer()) constants_[tensor.name()] = &tensor;
    for (const onnx::NodeProto& node : graph.node()) {
      for (const std::string& output : node.output()) producer_[output] = &node;
      for (const std::string& input : node.input()) readers_[input].push_back(&node);
      if (node.op_type() == "Constant" && node.output_size() == 1) {
        for (const onnx::AttributeProto& attribute : node.attribute()) {
          if (attribute.name() == "value" && attribute.has_t()) {
            constants_[node.output(0)] = &attribute.t();
          }
        }
      }
    }
  }

  const onnx::NodeProto* Producer(const std::string& tensor, const char* op_type) const {
    const auto it = producer_.find(tensor);
    return it != producer_.end() && it->second->op_type() == op_type ? it->second : nullptr;
  }

  bool ReadBy(const std::string& tensor, const char* op_type) const {
    const auto it = readers_.find(tensor);
    if (it == readers_.end()) return false;
    for (const onnx::NodeProto* reader : it->second) {
      if (reader->op_type() == op_type) return true;
    }
    return false;
  }

  // The output channels of the Conv producing 'tensor' (its weight's first dimension); -1 when
  // 'tensor' is no Conv's output or the weight is not a constant 4-D tensor.
  std::int64_t ConvChannels(const std::string& tensor) const {
    const onnx::NodeProto* conv = Producer(tensor, "Conv");
    if (conv == nullptr || conv->input_size() < 2) return -1;
    const auto weight = constants_.find(conv->input(1));
    if (weight == constants_.end() || weight->second->dims_size() != 4) return -1;
    return weight->second->dims(0);
  }

  // The tensors 'output' is computed from, itself included.
  std::unordered_set<std::string> Ancestors(const std::string& output) const {
    std::unordered_set<std::string> seen = {output};
    std::vector<std::string> stack = {output};
    while (!stack.empty()) {
      const std::string tensor = std::move(stack.back());
      stack.pop_back();
      const auto it = producer_.find(tensor);
      if (it == producer_.end()) continue;
      for (const std::string& input : it->second->input()) {
        if (!input.empty() && seen.insert(input).second) stack.push_back(input);
      }
    }
    return seen;
  }

 private:
  std::unordered_map<std::string, const onnx::NodeProto*> producer_;
  std::unordered_map<std::string, std::vector<const onnx::NodeProto*>> readers_;
  std::unordered_map<std::string, const onnx::TensorProto*> constants_;
};

// A Concat on 'axes' (the attribute), or false.
bool IsConcatOn(const onnx::NodeProto& node, std::initializer_list<std::int64_t> axes) {
  if (node.op_type() != "Concat" || node.output_size() != 1) return false;
  for (const onnx::AttributeProto& attribute : node.attribute()) {
    if (attribute.name() != "axis") continue;
    for (const std::int64_t axis : axes) {
      if (attribute.i() == axis) return true;
    }
  }
  return false;
}

// The tensor a Reshape producing 'tensor' reshapes, or empty.
std::string Unreshaped(const GraphIndex& index, const std::string& tensor) {
  const onnx::NodeProto* reshape = index.Producer(tensor, "Reshape");
  return reshape == nullptr || reshape->input_size() < 1 ? std::string() : reshape->input(0);
}

// The class count when 'level' is the channel Concat of a 64-channel box Conv and a class Conv
// (one stride of a joined head), else -1.
std::int64_t JoinedLevelClasses(const GraphIndex& index, const std::string& level) {
  const onnx::NodeProto* concat = index.Producer(level, "Concat");
  if (concat == nullptr || !IsConcatOn(*concat, {1, -3}) || concat->input_size() != 2) return -1;
  if (index.ConvChannels(concat->input(0)) != 4 * kRegMax) return -1;
  const std::int64_t classes = index.ConvChannels(concat->input(1));
  return classes > 0 ? classes : -1;
}

// For a Concat over the anchors (axis 2) whose inputs are all reshaped from 'level_channels'
// of the same value: that value, else -1.
template <typename LevelChannels>
std::int64_t SameForEveryLevel(const GraphIndex& index, const onnx::NodeProto& concat,
                               LevelChannels level_channels) {
  if (!IsConcatOn(concat, {2, -1}) || concat.input_size() < 1) return -1;
  std::int64_t channels = -1;
  for (const std::string& input : concat.input()) {
    const std::string level = Unreshaped(index, input);
    const std::int64_t c = level.empty() ? -1 : level_channels(level);
    if (c <= 0 || (channels > 0 && c != channels)) return -1;
    channels = c;
  }
  return channels;
}

std::string UniqueName(const onnx::GraphProto& graph, const std::string& stem) {
  std::unordered_set<std::string> used;
  for (const onnx::NodeProto& node : graph.node()) {
    used.insert(node.name());
    used.insert(node.output().begin(), node.output().end());
  }
  for (const onnx::TensorProto& tensor : graph.initializer()) used.insert(tensor.name());
  for (const onnx::ValueInfoProto& value : graph.input()) used.insert(value.name());
  std::string name = stem;
  for (int suffix = 1; used.count(name) > 0; ++suffix) name = stem + "_" + std::to_string(suffix);
  return name;
}

template <typename Repeated, typename Keep>
void KeepOnly(Repeated* items, Keep keep) {
  Repeated kept;
  for (auto& item : *items) {
    if (keep(item)) *kept.Add() = std::move(item);
  }
  items->Swap(&kept);
}

}  // namespace

std::optional<RawHeadInGraph> FindRawHead(const onnx::GraphProto& graph) {
  if (graph.output_size() == 0) return std::nullopt;
  const GraphIndex index(graph);
  const std::unordered_set<std::string> used = index.Ancestors(graph.output(0).name());
  std::vector<RawHeadInGraph> boxes, classes;  // the stacks of a separate head
  for (const onnx::NodeProto& node : graph.node()) {
    if (!IsConcatOn(node, {2, -1}) || used.count(node.output(0)) == 0) continue;
    const int strides = node.input_size();
    const std::int64_t joined = SameForEveryLevel(
        index, node, [&](const std::string& level) { return JoinedLevelClasses(index, level); });
    if (joined > 0) return RawHeadInGraph{node.output(0), "", static_cast<int>(joined), strides};
    const std::int64_t channels = SameForEveryLevel(
        index, node, [&](const std::string& level) { return index.ConvChannels(level); });
    if (channels <= 0) continue;
    const RawHeadInGraph stack{node.output(0), "", static_cast<int>(channels), strides};
    if (index.ReadBy(node.output(0), "Sigmoid")) {
      classes.push_back(stack);
    } else if (channels == 4 * kRegMax) {
      boxes.push_back(stack);
    }
  }
  for (const RawHeadInGraph& box : boxes) {
    for (const RawHeadInGraph& cls : classes) {
      if (cls.strides == box.strides) {
        return RawHeadInGraph{box.tensor, cls.tensor, cls.classes, box.strides};
      }
    }
  }
  return std::nullopt;
}

bool CutAtRawHead(onnx::GraphProto* graph, const RawHeadInGraph& head) {
  std::string tensor = head.tensor;
  if (!head.class_tensor.empty()) {
    tensor = UniqueName(*graph, "semchain_raw_head");
    onnx::NodeProto* concat = graph->add_node();
    concat->set_op_type("Concat");
    concat->set_name(tensor);
    concat->add_input(head.tensor);
    concat->add_input(head.class_tensor);
    concat->add_output(tensor);
    onnx::AttributeProto* axis = concat->add_attribute();
    axis->set_name("axis");
    axis->set_type(onnx::AttributeProto::INT);
    axis->set_i(1);
  }
  if (graph->output_size() == 1 && graph->output(0).name() == tensor) return false;
  // Walking backwards from the head: a node is kept when one of its outputs is needed.
  std::unordered_set<std::string> needed = {tensor};
  std::vector<bool> keep(static_cast<std::size_t>(graph->node_size()), false);
  for (int i = graph->node_size() - 1; i >= 0; --i) {
    const onnx::NodeProto& node = graph->node(i);
    for (const std::string& output : node.output()) {
      if (needed.count(output) > 0) keep[static_cast<std::size_t>(i)] = true;
    }
    if (!keep[static_cast<std::size_t>(i)]) continue;
    for (const std::string& input : node.input()) {
      if (!input.empty()) needed.insert(input);
    }
  }
  std::size_t position = 0;
  KeepOnly(graph->mutable_node(), [&](const onnx::NodeProto&) { return keep[position++]; });
  KeepOnly(graph->mutable_initializer(),
           [&](const onnx::TensorProto& t) { return needed.count(t.name()) > 0; });
  KeepOnly(graph->mutable_input(),
           [&](const onnx::ValueInfoProto& v) { return needed.count(v.name()) > 0; });
  KeepOnly(graph->mutable_value_info(),
           [&](const onnx::ValueInfoProto& v) { return needed.count(v.name()) > 0; });
  graph->clear_output();
  onnx::ValueInfoProto* output = graph->add_output();
  output->set_name(tensor);
  onnx::TypeProto::Tensor* type = output->mutable_type()->mutable_tensor_type();
  type->set_elem_type(onnx::TensorProto::FLOAT);
  onnx::TensorShapeProto* shape = type->mutable_shape();
  shape->add_dim()->set_dim_value(1);
  shape->add_dim()->set_dim_value(4 * kRegMax + head.classes);
  shape->add_dim()->set_dim_param("anchors");  // OpenCV needs a shape, not its values
  return true;
}

}  // namespace semchain::detection
