#include "detection/onnx_model_prepare.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>

#include "core/atomic_file.h"
#include "detection/onnx_raw_head.h"
#include "detection/testing/onnx_builder.h"
#include "detection/testing/square_scene.h"

namespace semchain::detection {
namespace {

using onnx::TensorProto;
using testing::OnnxBuilder;
using testing::RunOpenCv;
using testing::TestModel;

onnx::ModelProto ReadModel(const std::string& file) {
  const Result<std::string> bytes = ReadFile(TestModel(file));
  EXPECT_TRUE(bytes.ok()) << bytes.status().message();
  onnx::ModelProto model;
  EXPECT_TRUE(bytes.ok() && model.ParseFromString(*bytes));
  return model;
}

std::multiset<std::string> OpTypes(const onnx::GraphProto& graph) {
  std::multiset<std::string> types;
  for (const onnx::NodeProto& node : graph.node()) types.insert(node.op_type());
  return types;
}

// ultralytics' default export: the raw head is the Concat the decoding's Split reads, and the
// cut leaves the network up to it: no DFL Softmax, no anchors, no Sigmoid on the classes.
TEST(RawHeadTest, FindsTheJoinedHeadOfTheDecodedExportAndCutsItsDecoding) {
  onnx::ModelProto model = ReadModel("ultralytics_decoded.onnx");
  const std::optional<RawHeadInGraph> head = FindRawHead(model.graph());
  ASSERT_TRUE(head.has_value());
  EXPECT_EQ(head->classes, 80);
  EXPECT_EQ(head->strides, 3);
  EXPECT_TRUE(head->class_tensor.empty());
  std::string split_input;
  for (const onnx::NodeProto& node : model.graph().node()) {
    if (node.op_type() == "Split" && node.output_size() == 2 && split_input.empty() &&
        node.name().find("detect") != std::string::npos) {
      split_input = node.input(0);
    }
  }
  EXPECT_EQ(head->tensor, split_input);
  const std::multiset<std::string> before = OpTypes(model.graph());
  ASSERT_TRUE(CutAtRawHead(model.mutable_graph(), *head));
  ASSERT_EQ(model.graph().output_size(), 1);
  EXPECT_EQ(model.graph().output(0).name(), head->tensor);
  const std::multiset<std::string> after = OpTypes(model.graph());
  EXPECT_EQ(after.count("Softmax"), 0u);
  EXPECT_EQ(after.count("Transpose"), 0u);
  EXPECT_EQ(after.count("Conv"), before.count("Conv") - 1);  // the DFL convolution
  EXPECT_EQ(after.count("Sigmoid"), before.count("Sigmoid") - 1);
  EXPECT_EQ(after.count("Split"), before.count("Split") - 1);
  for (const TensorProto& tensor : model.graph().initializer()) {
    EXPECT_EQ(tensor.name().find("dfl"), std::string::npos) << tensor.name();
  }
}

TEST(RawHeadTest, FindsTheRawExportsHeadAndLeavesItWhole) {
  onnx::ModelProto model = ReadModel("ultralytics_raw.onnx");
  const std::optional<RawHeadInGraph> head = FindRawHead(model.graph());
  ASSERT_TRUE(head.has_value());
  EXPECT_EQ(head->classes, 80);
  EXPECT_EQ(head->tensor, model.graph().output(0).name());
  const int nodes = model.graph().node_size();
  EXPECT_FALSE(CutAtRawHead(model.mutable_graph(), *head));
  EXPECT_EQ(model.graph().node_size(), nodes);
}

TEST(RawHeadTest, FindsNoHeadInAHandMadeModel) {
  EXPECT_FALSE(FindRawHead(ReadModel("tiny_squares_raw.onnx").graph()).has_value());
  EXPECT_FALSE(FindRawHead(ReadModel("tiny_squares_decoded.onnx").graph()).has_value());
}

// The head of later ultralytics versions: the box maps and the class maps are concatenated over
// the strides separately (the class maps then go through a Sigmoid). Three "strides" of 1 × 1
// convolutions on a 3-channel 4 × 4 input, two classes.
OnnxBuilder SeparateHead() {
  OnnxBuilder b;
  b.Input("images", TensorProto::FLOAT, {1, 3, 4, 4});
  b.Int64s("box_shape", {1, 64, -1});
  b.Int64s("cls_shape", {1, 2, -1});
  for (int level = 0; level < 3; ++level) {
    const std::string l = std::to_string(level);
    std::vector<float> box(64 * 3), cls(2 * 3);
    for (std::size_t i = 0; i < box.size(); ++i) box[i] = float(i % 7) - 3.0f + float(level);
    for (std::size_t i = 0; i < cls.size(); ++i) cls[i] = float(i) - 2.5f * float(level);
    b.Floats("box_w" + l, {64, 3, 1, 1}, box);
    b.Floats("cls_w" + l, {2, 3, 1, 1}, cls);
    OnnxBuilder::IntsAttribute(b.Node("Conv", {"images", "box_w" + l}, {"box" + l}), "kernel_shape",
                               {1, 1});
    OnnxBuilder::IntsAttribute(b.Node("Conv", {"images", "cls_w" + l}, {"cls" + l}), "kernel_shape",
                               {1, 1});
    b.Node("Reshape", {"box" + l, "box_shape"}, {"box_flat" + l});
    b.Node("Reshape", {"cls" + l, "cls_shape"}, {"cls_flat" + l});
  }
  OnnxBuilder::IntAttribute(b.Node("Concat", {"box_flat0", "box_flat1", "box_flat2"}, {"boxes"}),
                            "axis", -1);
  OnnxBuilder::IntAttribute(b.Node("Concat", {"cls_flat0", "cls_flat1", "cls_flat2"}, {"scores"}),
                            "axis", -1);
  b.Node("Sigmoid", {"scores"}, {"probabilities"});
  b.Node("Softmax", {"boxes"}, {"decoded"});  // stands for the DFL decoding
  OnnxBuilder::IntAttribute(b.Node("Concat", {"decoded", "probabilities"}, {"output0"}), "axis", 1);
  b.Output("output0", TensorProto::FLOAT, {1, 66, 48});
  return b;
}

TEST(RawHeadTest, JoinsASeparateHeadsBoxAndClassMaps) {
  OnnxBuilder b = SeparateHead();
  const std::optional<RawHeadInGraph> head = FindRawHead(b.model().graph());
  ASSERT_TRUE(head.has_value());
  EXPECT_EQ(head->tensor, "boxes");
  EXPECT_EQ(head->class_tensor, "scores");
  EXPECT_EQ(head->classes, 2);
  ASSERT_TRUE(CutAtRawHead(b.model().mutable_graph(), *head));
  const std::string output = b.model().graph().output(0).name();
  EXPECT_EQ(output, "semchain_raw_head");
  EXPECT_EQ(OpTypes(b.model().graph()).count("Sigmoid"), 0u);
  // OpenCV runs it: the raw head is the 64 box rows, then the 2 class rows, of the 3 × 16
  // anchors; a pixel of ones gives each row its weights' sum.
  const int shape[] = {1, 3, 4, 4};
  const cv::Mat ones(4, shape, CV_32F, cv::Scalar(1.0f));
  const std::vector<cv::Mat> out = RunOpenCv(b.Bytes(), ones, {output});
  ASSERT_EQ(out.size(), 1u);
  ASSERT_EQ(out[0].dims, 3);
  EXPECT_EQ(out[0].size[1], 66);
  EXPECT_EQ(out[0].size[2], 48);
  const float* data = out[0].ptr<float>();
  // Row 65 (class 1), anchor 40 (level 2): the weights 3, 4, 5 minus 2.5 · 2 each.
  EXPECT_FLOAT_EQ(data[65 * 48 + 40], 3.0f + 4.0f + 5.0f - 15.0f);
  // Row 0 (box), anchor 0 (level 0): weights i % 7 - 3 for i = 0, 1, 2.
  EXPECT_FLOAT_EQ(data[0], -3.0f - 2.0f - 1.0f);
}

TEST(PrepareOnnxModelTest, CutsTheDefaultExportAndReadsItsNames) {
  const Result<std::string> bytes = ReadFile(TestModel("ultralytics_decoded.onnx"));
  ASSERT_TRUE(bytes.ok());
  Result<PreparedOnnxModel> prepared = PrepareOnnxModel(*bytes, "decoded.onnx");
  ASSERT_TRUE(prepared.ok()) << prepared.status().message();
  EXPECT_EQ(prepared->head_classes, 80);
  EXPECT_EQ(prepared->head_strides, 3);
  EXPECT_TRUE(prepared->decoding_removed);
  EXPECT_EQ(prepared->float16_tensors, 0);
  EXPECT_GT(prepared->split_nodes, 0);  // C2f's split() at opset 17
  ASSERT_EQ(prepared->class_names.size(), 80u);
  EXPECT_EQ(prepared->class_names[0], "person");
  EXPECT_EQ(prepared->class_names[79], "toothbrush");
  EXPECT_LT(prepared->bytes.size(), bytes->size());
}

TEST(PrepareOnnxModelTest, ConvertsTheHalfPrecisionExport) {
  const Result<std::string> bytes = ReadFile(TestModel("ultralytics_decoded_fp16.onnx"));
  ASSERT_TRUE(bytes.ok());
  Result<PreparedOnnxModel> prepared = PrepareOnnxModel(*bytes, "fp16.onnx");
  ASSERT_TRUE(prepared.ok()) << prepared.status().message();
  EXPECT_GT(prepared->float16_tensors, 50);
  EXPECT_TRUE(prepared->decoding_removed);
  onnx::ModelProto model;
  ASSERT_TRUE(model.ParseFromString(prepared->bytes));
  for (const TensorProto& tensor : model.graph().initializer()) {
    EXPECT_NE(tensor.data_type(), TensorProto::FLOAT16) << tensor.name();
  }
  EXPECT_EQ(model.graph().input(0).type().tensor_type().elem_type(), TensorProto::FLOAT);
}

TEST(PrepareOnnxModelTest, HandsAModelWithNothingToRewriteOnAsItIs) {
  const Result<std::string> bytes = ReadFile(TestModel("tiny_squares_raw.onnx"));
  ASSERT_TRUE(bytes.ok());
  Result<PreparedOnnxModel> prepared = PrepareOnnxModel(*bytes, "tiny.onnx");
  ASSERT_TRUE(prepared.ok()) << prepared.status().message();
  EXPECT_FALSE(prepared->head_classes.has_value());
  EXPECT_FALSE(prepared->decoding_removed);
  EXPECT_TRUE(prepared->class_names.empty());
  EXPECT_EQ(prepared->bytes, *bytes);
}

TEST(PrepareOnnxModelTest, ReportsUnreadableMetadataNames) {
  OnnxBuilder b = SeparateHead();
  onnx::StringStringEntryProto* names = b.model().add_metadata_props();
  names->set_key("names");
  names->set_value("{0: 'a', 2: 'c'}");
  Result<PreparedOnnxModel> prepared = PrepareOnnxModel(b.Bytes(), "m.onnx");
  ASSERT_TRUE(prepared.ok()) << prepared.status().message();
  EXPECT_TRUE(prepared->class_names.empty());
  EXPECT_EQ(prepared->names_error, "metadata 'names': class ids are not 0 to 1 (id 1 is missing)");
}

TEST(PrepareOnnxModelTest, RejectsBytesThatAreNoModel) {
  Result<PreparedOnnxModel> prepared = PrepareOnnxModel("\x0a\xff\xff", "m.onnx");
  ASSERT_FALSE(prepared.ok());
  EXPECT_EQ(prepared.status().message(), "m.onnx: not an ONNX model (malformed protobuf)");
}

}  // namespace
}  // namespace semchain::detection
