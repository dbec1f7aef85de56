#pragma once

#include <onnx/onnx_pb.h>

#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>
#include <string>
#include <vector>

// Small ONNX graphs written in the tests themselves (onnx::ModelProto), for the rewrites of
// onnx_rewrite.h and onnx_raw_head.h, and the means to run them through OpenCV DNN.
namespace semchain::detection::testing {

class OnnxBuilder {
 public:
  explicit OnnxBuilder(int opset = 17) {
    model_.set_ir_version(8);
    model_.add_opset_import()->set_version(opset);
    graph_ = model_.mutable_graph();
    graph_->set_name("test");
  }

  // A graph input or output of element type 'type' and shape 'dims'.
  void Input(const std::string& name, int type, std::initializer_list<std::int64_t> dims) {
    Describe(graph_->add_input(), name, type, dims);
  }
  void Output(const std::string& name, int type, std::initializer_list<std::int64_t> dims) {
    Describe(graph_->add_output(), name, type, dims);
  }

  // A FLOAT (or, with 'half', FLOAT16) initializer of shape 'dims'.
  void Floats(const std::string& name, std::initializer_list<std::int64_t> dims,
              const std::vector<float>& values, bool half = false) {
    FillFloats(graph_->add_initializer(), name, dims, values, half);
  }
  void Int64s(const std::string& name, const std::vector<std::int64_t>& values) {
    onnx::TensorProto* tensor = graph_->add_initializer();
    tensor->set_name(name);
    tensor->set_data_type(onnx::TensorProto::INT64);
    tensor->add_dims(static_cast<std::int64_t>(values.size()));
    tensor->set_raw_data(values.data(), values.size() * sizeof(std::int64_t));
  }
  // A Constant node holding FLOAT16 'values' in int32_data (the other way ONNX stores halves).
  void HalfConstant(const std::string& name, std::initializer_list<std::int64_t> dims,
                    const std::vector<float>& values) {
    onnx::NodeProto* node = Node("Constant", {}, {name});
    onnx::AttributeProto* value = node->add_attribute();
    value->set_name("value");
    value->set_type(onnx::AttributeProto::TENSOR);
    onnx::TensorProto* tensor = value->mutable_t();
    FillFloats(tensor, "", dims, values, true);
    const std::string raw = tensor->raw_data();
    tensor->clear_raw_data();
    for (std::size_t i = 0; i + 1 < raw.size(); i += 2) {
      std::uint16_t bits = 0;
      std::memcpy(&bits, raw.data() + i, 2);
      tensor->add_int32_data(bits);
    }
  }

  onnx::NodeProto* Node(const std::string& op_type, std::initializer_list<std::string> inputs,
                        std::initializer_list<std::string> outputs) {
    onnx::NodeProto* node = graph_->add_node();
    node->set_op_type(op_type);
    node->set_name(op_type + "_" + std::to_string(graph_->node_size()));
    for (const std::string& input : inputs) node->add_input(input);
    for (const std::string& output : outputs) node->add_output(output);
    return node;
  }
  static void IntAttribute(onnx::NodeProto* node, const std::string& name, std::int64_t value) {
    onnx::AttributeProto* attribute = node->add_attribute();
    attribute->set_name(name);
    attribute->set_type(onnx::AttributeProto::INT);
    attribute->set_i(value);
  }
  static void IntsAttribute(onnx::NodeProto* node, const std::string& name,
                            std::initializer_list<std::int64_t> values) {
    onnx::AttributeProto* attribute = node->add_attribute();
    attribute->set_name(name);
    attribute->set_type(onnx::AttributeProto::INTS);
    for (const std::int64_t value : values) attribute->add_ints(value);
  }

  onnx::ModelProto& model() { return model_; }
  std::string Bytes() const { return model_.SerializeAsString(); }

 private:
  static void Describe(onnx::ValueInfoProto* value, const std::string& name, int type,
                       std::initializer_list<std::int64_t> dims) {
    value->set_name(name);
    onnx::TypeProto::Tensor* tensor = value->mutable_type()->mutable_tensor_type();
    tensor->set_elem_type(type);
    for (const std::int64_t dim : dims) tensor->mutable_shape()->add_dim()->set_dim_value(dim);
  }

  static void FillFloats(onnx::TensorProto* tensor, const std::string& name,
                         std::initializer_list<std::int64_t> dims, const std::vector<float>& values,
                         bool half) {
    tensor->set_name(name);
    for (const std::int64_t dim : dims) tensor->add_dims(dim);
    if (!half) {
      tensor->set_data_type(onnx::TensorProto::FLOAT);
      tensor->set_raw_data(values.data(), values.size() * sizeof(float));
      return;
    }
    tensor->set_data_type(onnx::TensorProto::FLOAT16);
    cv::Mat halves;
    cv::Mat(1, static_cast<int>(values.size()), CV_32F, const_cast<float*>(values.data()))
        .convertTo(halves, CV_16F);
    tensor->set_raw_data(halves.data, values.size() * 2);
  }

  onnx::ModelProto model_;
  onnx::GraphProto* graph_;
};

// The outputs 'names' of 'bytes' run by OpenCV DNN on 'input' (an N-d CV_32F blob).
inline std::vector<cv::Mat> RunOpenCv(const std::string& bytes, const cv::Mat& input,
                                      const std::vector<std::string>& names) {
  cv::dnn::Net net = cv::dnn::readNetFromONNX(bytes.data(), bytes.size());
  net.setInput(input);
  std::vector<cv::Mat> outputs;
  net.forward(outputs, names);
  return outputs;
}

}  // namespace semchain::detection::testing
