#include "detection/onnx_rewrite.h"

#include <gtest/gtest.h>

#include "detection/testing/onnx_builder.h"

namespace semchain::detection {
namespace {

using onnx::TensorProto;
using testing::OnnxBuilder;
using testing::RunOpenCv;

std::vector<std::string> OpTypes(const onnx::ModelProto& model) {
  std::vector<std::string> types;
  for (const onnx::NodeProto& node : model.graph().node()) types.push_back(node.op_type());
  return types;
}

// y = Cast<float>(Cast<half>(x) * w + c): what an fp16 conversion with float inputs and outputs
// writes; w a FLOAT16 initializer, c a FLOAT16 Constant stored in int32_data.
OnnxBuilder HalfModel() {
  OnnxBuilder b;
  b.Input("x", TensorProto::FLOAT, {1, 2, 1, 1});
  b.Floats("w", {1, 2, 1, 1}, {0.5f, -3.0f}, /*half=*/true);
  b.HalfConstant("c", {1, 2, 1, 1}, {0.25f, 8.0f});
  OnnxBuilder::IntAttribute(b.Node("Cast", {"x"}, {"x_half"}), "to", TensorProto::FLOAT16);
  b.Node("Mul", {"x_half", "w"}, {"scaled"});
  b.Node("Add", {"scaled", "c"}, {"shifted"});
  OnnxBuilder::IntAttribute(b.Node("Cast", {"shifted"}, {"y"}), "to", TensorProto::FLOAT);
  b.Output("y", TensorProto::FLOAT, {1, 2, 1, 1});
  return b;
}

TEST(ConvertFloat16ToFloatTest, ConvertsWeightsConstantsAndTypesAndDropsCastsMadeRedundant) {
  OnnxBuilder b = HalfModel();
  onnx::ModelProto& model = b.model();
  EXPECT_EQ(ConvertFloat16ToFloat(&model), 2);  // w and c
  const TensorProto* w = FindConstantTensor(model.graph(), "w");
  const TensorProto* c = FindConstantTensor(model.graph(), "c");
  ASSERT_NE(w, nullptr);
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(w->data_type(), TensorProto::FLOAT);
  EXPECT_EQ(c->data_type(), TensorProto::FLOAT);
  // The Cast to half became a Cast of a float to float and is gone; the last Cast names the
  // graph's output and stays (a Cast of a computed tensor is an identity to OpenCV).
  EXPECT_EQ(OpTypes(model), (std::vector<std::string>{"Constant", "Mul", "Add", "Cast"}));
  EXPECT_EQ(model.graph().node(1).input(0), "x");
  const cv::Mat x = (cv::Mat_<float>(1, 2) << 2.0f, 1.5f);
  const int shape[] = {1, 2, 1, 1};
  const std::vector<cv::Mat> y = RunOpenCv(b.Bytes(), x.reshape(1, 4, shape), {"y"});
  ASSERT_EQ(y.size(), 1u);
  EXPECT_FLOAT_EQ(y[0].ptr<float>()[0], 2.0f * 0.5f + 0.25f);
  EXPECT_FLOAT_EQ(y[0].ptr<float>()[1], 1.5f * -3.0f + 8.0f);
}

TEST(ConvertFloat16ToFloatTest, MakesHalfInputsAndOutputsFloat) {
  OnnxBuilder b;
  b.Input("x", TensorProto::FLOAT16, {1, 1, 1, 1});
  b.Floats("w", {1, 1, 1, 1}, {2.0f}, /*half=*/true);
  b.Node("Mul", {"x", "w"}, {"y"});
  b.Output("y", TensorProto::FLOAT16, {1, 1, 1, 1});
  EXPECT_EQ(ConvertFloat16ToFloat(&b.model()), 3);
  EXPECT_EQ(b.model().graph().input(0).type().tensor_type().elem_type(), TensorProto::FLOAT);
  EXPECT_EQ(b.model().graph().output(0).type().tensor_type().elem_type(), TensorProto::FLOAT);
}

TEST(ConvertFloat16ToFloatTest, LeavesAFloatModelAsItIs) {
  OnnxBuilder b;
  b.Input("x", TensorProto::FLOAT, {1, 1, 1, 1});
  b.Floats("w", {1, 1, 1, 1}, {2.0f});
  OnnxBuilder::IntAttribute(b.Node("Cast", {"x"}, {"x_float"}), "to", TensorProto::FLOAT);
  b.Node("Mul", {"x_float", "w"}, {"y"});
  b.Output("y", TensorProto::FLOAT, {1, 1, 1, 1});
  const std::string before = b.Bytes();
  EXPECT_EQ(ConvertFloat16ToFloat(&b.model()), 0);
  EXPECT_EQ(b.Bytes(), before);
}

// OpenCV 4.6 reads a Split's sizes only from its 'split' attribute (opset 11 and 12); given as
// the second input (opset 13 and later) they are ignored and the channels split evenly.
TEST(MoveSplitSizesToAttributesTest, GivesOpenCvTheSizesOfAnUnevenSplit) {
  OnnxBuilder b;
  b.Input("x", TensorProto::FLOAT, {1, 4, 1, 1});
  b.Int64s("sizes", {1, 3});
  OnnxBuilder::IntAttribute(b.Node("Split", {"x", "sizes"}, {"a", "b"}), "axis", 1);
  b.Output("a", TensorProto::FLOAT, {1, 1, 1, 1});
  b.Output("b", TensorProto::FLOAT, {1, 3, 1, 1});
  EXPECT_EQ(MoveSplitSizesToAttributes(b.model().mutable_graph()), 1);
  const onnx::NodeProto& split = b.model().graph().node(0);
  ASSERT_EQ(split.input_size(), 1);
  const onnx::AttributeProto* sizes = nullptr;
  for (const onnx::AttributeProto& attribute : split.attribute()) {
    if (attribute.name() == "split") sizes = &attribute;
  }
  ASSERT_NE(sizes, nullptr);
  EXPECT_EQ(std::vector<std::int64_t>(sizes->ints().begin(), sizes->ints().end()),
            (std::vector<std::int64_t>{1, 3}));
  const cv::Mat x = (cv::Mat_<float>(1, 4) << 1.0f, 2.0f, 3.0f, 4.0f);
  const int shape[] = {1, 4, 1, 1};
  const std::vector<cv::Mat> out = RunOpenCv(b.Bytes(), x.reshape(1, 4, shape), {"a", "b"});
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].total(), 1u);
  EXPECT_EQ(out[1].total(), 3u);
  EXPECT_FLOAT_EQ(out[1].ptr<float>()[2], 4.0f);
}

TEST(MoveSplitSizesToAttributesTest, LeavesComputedSizesAndAttributeSplits) {
  OnnxBuilder b;
  b.Input("x", TensorProto::FLOAT, {1, 4, 1, 1});
  b.Input("sizes", TensorProto::INT64, {2});  // not a constant
  b.Node("Split", {"x", "sizes"}, {"a", "b"});
  OnnxBuilder::IntsAttribute(b.Node("Split", {"x"}, {"c", "d"}), "split", {2, 2});
  EXPECT_EQ(MoveSplitSizesToAttributes(b.model().mutable_graph()), 0);
  EXPECT_EQ(b.model().graph().node(0).input_size(), 2);
}

TEST(ReadIntegersTest, ReadsInt64AndInt32AndRejectsOtherTypes) {
  OnnxBuilder b;
  b.Int64s("sizes", {64, 80});
  std::vector<std::int64_t> values;
  ASSERT_TRUE(ReadIntegers(*FindConstantTensor(b.model().graph(), "sizes"), &values));
  EXPECT_EQ(values, (std::vector<std::int64_t>{64, 80}));
  TensorProto narrow;
  narrow.set_data_type(TensorProto::INT32);
  narrow.add_dims(2);
  narrow.add_int32_data(-1);
  narrow.add_int32_data(7);
  ASSERT_TRUE(ReadIntegers(narrow, &values));
  EXPECT_EQ(values, (std::vector<std::int64_t>{-1, 7}));
  narrow.add_int32_data(9);  // three values for two elements
  EXPECT_FALSE(ReadIntegers(narrow, &values));
  b.Floats("w", {1}, {1.0f});
  EXPECT_FALSE(ReadIntegers(*FindConstantTensor(b.model().graph(), "w"), &values));
  EXPECT_EQ(FindConstantTensor(b.model().graph(), "nothing"), nullptr);
}

}  // namespace
}  // namespace semchain::detection
