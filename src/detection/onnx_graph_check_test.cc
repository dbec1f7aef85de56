#include "detection/onnx_graph_check.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "detection/testing/square_scene.h"

namespace semchain::detection {
namespace {

using ::testing::HasSubstr;

// Protobuf wire format by hand: a length-delimited field is the key (number << 3 | 2), the
// length as a varint (all lengths here are below 128: one byte), then the bytes.
std::string Field(int number, const std::string& bytes) {
  return std::string(1, static_cast<char>(number << 3 | 2)) +
         std::string(1, static_cast<char>(bytes.size())) + bytes;
}

std::string Node(const std::vector<std::string>& inputs, const std::string& output,
                 const std::string& op_type) {
  std::string node;
  for (const std::string& input : inputs) node += Field(1, input);
  return node + Field(2, output) + Field(4, op_type);
}

// TensorShapeProto.Dimension: dim_value = 1 (varint, values below 128 here) or dim_param = 2.
std::string Dim(int value) { return std::string(1, '\x08') + static_cast<char>(value); }
std::string SymbolicDim(const std::string& name) { return Field(2, name); }

// TensorProto { dims: 'dims' (unpacked); data_type FLOAT; name; raw_data of 'raw_bytes' }.
std::string FloatTensor(const std::string& name, const std::vector<int>& dims, int raw_bytes) {
  std::string tensor;
  for (const int dim : dims) tensor += Dim(dim);  // field 1, varint
  tensor += std::string("\x10\x01", 2);           // data_type = 1 (FLOAT)
  tensor += Field(8, name);
  return tensor + Field(9, std::string(static_cast<std::size_t>(raw_bytes), '\0'));
}

// ModelProto { graph { input x; initializer w; nodes; output y } }.
std::string Model(const std::vector<std::string>& nodes, const std::string& output = "y") {
  std::string graph = Field(11, Field(1, "x")) + Field(5, FloatTensor("w", {1}, 4));
  for (const std::string& node : nodes) graph += Field(1, node);
  graph += Field(12, Field(1, output));
  return std::string("\x08\x07", 2) + Field(7, graph);  // ir_version = 7, then the graph
}

TEST(OnnxGraphCheck, AcceptsASortedGraph) {
  const std::string model =
      Model({Node({"x", "w"}, "h", "Conv"), Node({"h", ""}, "y", "Relu")});  // "" = no input
  EXPECT_TRUE(CheckOnnxGraph(model, "m.onnx").ok());
}

TEST(OnnxGraphCheck, RejectsAnInputNoEarlierNodeProduces) {
  const Status status =
      CheckOnnxGraph(Model({Node({"h"}, "y", "Relu"), Node({"x", "w"}, "h", "Conv")}), "m.onnx");
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message(),
            "m.onnx: ONNX node 0 (Relu) reads 'h', which no graph input, initializer or earlier "
            "node provides");
}

TEST(OnnxGraphCheck, RejectsAnOutputNoNodeProduces) {
  const Status status = CheckOnnxGraph(Model({Node({"x"}, "h", "Relu")}, "z"), "m.onnx");
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("graph output 'z' is produced by no node"));
}

TEST(OnnxGraphCheck, RejectsTruncatedAndForeignBytes) {
  const std::string model = Model({Node({"x", "w"}, "y", "Conv")});
  for (std::size_t size = 1; size < model.size(); ++size) {
    EXPECT_FALSE(CheckOnnxGraph(model.substr(0, size), "m.onnx").ok()) << size;
  }
  EXPECT_EQ(CheckOnnxGraph("", "m.onnx").message(), "m.onnx: not an ONNX model (no graph)");
  EXPECT_EQ(CheckOnnxGraph("P5\n8 6\n255\n", "m.onnx").message(),
            "m.onnx: not an ONNX model (malformed protobuf)");
}

TEST(OnnxGraphCheck, AcceptsTheTestModels) {
  for (const char* name : {"tiny_squares_raw.onnx", "tiny_squares_decoded.onnx"}) {
    const Result<std::string> bytes = ReadFile(testing::TestModel(name));
    ASSERT_TRUE(bytes.ok()) << bytes.status().message();
    const Status status = CheckOnnxGraph(*bytes, name);
    EXPECT_TRUE(status.ok()) << status.message();
  }
}

// A model whose graph input 'name' has the shape 'dims' (ValueInfoProto.type.tensor_type.shape),
// listed after an initializer that is also a graph input (older exporters list weights so).
std::string ModelWithInput(const std::string& name, const std::vector<std::string>& dims) {
  std::string shape;
  for (const std::string& dim : dims) shape += Field(1, dim);
  const std::string input = Field(1, name) + Field(2, Field(1, Field(2, shape)));
  const std::string weight_input = Field(1, "w") + Field(2, Field(1, Field(2, Field(1, Dim(3)))));
  const std::string graph = Field(5, Field(8, "w")) + Field(11, weight_input) + Field(11, input) +
                            Field(12, Field(1, "y"));
  return Field(7, graph);
}

TEST(OnnxStaticInputSize, ReadsHeightAndWidthOfTheImageInput) {
  EXPECT_EQ(OnnxStaticInputSize(ModelWithInput("images", {Dim(1), Dim(3), Dim(96), Dim(64)})),
            std::make_optional(std::pair(64, 96)));
  // Dynamic (symbolic) sizes, another rank, no graph: nothing to read.
  EXPECT_EQ(OnnxStaticInputSize(
                ModelWithInput("images", {Dim(1), Dim(3), SymbolicDim("h"), SymbolicDim("w")})),
            std::nullopt);
  EXPECT_EQ(OnnxStaticInputSize(ModelWithInput("images", {Dim(1), Dim(96), Dim(64)})),
            std::nullopt);
  EXPECT_EQ(OnnxStaticInputSize(""), std::nullopt);
  EXPECT_EQ(OnnxStaticInputSize(
                ModelWithInput("images", {Dim(1), Dim(3), Dim(96), Dim(64)}).substr(0, 20)),
            std::nullopt);
}

TEST(OnnxStaticInputSize, ReadsTheTestModelsExportSize) {
  const Result<std::string> bytes = ReadFile(testing::TestModel("tiny_squares_raw.onnx"));
  ASSERT_TRUE(bytes.ok()) << bytes.status().message();
  EXPECT_EQ(OnnxStaticInputSize(*bytes), std::make_optional(std::pair(640, 640)));
}

std::string ModelWithInitializer(const std::string& tensor) {
  const std::string graph = Field(11, Field(1, "x")) + Field(5, tensor) +
                            Field(1, Node({"x", "w"}, "y", "Add")) + Field(12, Field(1, "y"));
  return Field(7, graph);
}

// OpenCV 4.6 copies as many bytes as the dims say from whatever raw data the file holds: a
// heap overflow on a short tensor (found by fuzz/onnx_model_fuzzer.cc,
// fuzz/crashes/onnx_model/tensor_shorter_than_its_dims.bin).
TEST(OnnxGraphCheck, RejectsATensorWhoseDataIsNotItsShapes) {
  EXPECT_TRUE(CheckOnnxGraph(ModelWithInitializer(FloatTensor("w", {2, 3}, 24)), "m.onnx").ok());
  EXPECT_EQ(CheckOnnxGraph(ModelWithInitializer(FloatTensor("w", {2, 3}, 20)), "m.onnx").message(),
            "m.onnx: ONNX initializer tensor 'w': 20 bytes of raw data for 6 elements of 4 bytes");
  EXPECT_THAT(
      CheckOnnxGraph(ModelWithInitializer(FloatTensor("w", {100, 100, 100, 100}, 4)), "m.onnx")
          .message(),
      HasSubstr("bytes of raw data for 100000000 elements"));
  // The same in a Constant node's value attribute (AttributeProto.t = 5).
  const std::string constant = Field(2, "w") + Field(4, "Constant") +
                               Field(5, Field(1, "value") + Field(5, FloatTensor("", {4}, 8)));
  const std::string graph = Field(11, Field(1, "x")) + Field(1, constant) +
                            Field(1, Node({"x", "w"}, "y", "Add")) + Field(12, Field(1, "y"));
  EXPECT_THAT(CheckOnnxGraph(Field(7, graph), "m.onnx").message(),
              HasSubstr("ONNX node 0 attribute tensor '': 8 bytes of raw data for 4 elements"));
}

// A Conv with group 0 divided by zero inside OpenCV 4.6 (found by fuzz/onnx_model_fuzzer.cc,
// fuzz/crashes/onnx_model/conv_group_zero.bin); a stride of 0 would too.
TEST(OnnxGraphCheck, RejectsSizesOpenCvDividesBy) {
  const auto conv = [](const std::string& attribute) {
    const std::string node = Node({"x", "w"}, "y", "Conv") + Field(5, attribute);
    return Model({node});
  };
  const std::string group_one = Field(1, "group") + std::string("\x18\x01", 2);  // i = 1
  const std::string group_zero = Field(1, "group") + std::string("\x18\x00", 2);
  const std::string packed_strides = Field(1, "strides") + Field(8, std::string("\x01\x00", 2));
  const std::string other = Field(1, "pads") + Field(8, std::string("\x00\x00", 2));
  EXPECT_TRUE(CheckOnnxGraph(conv(group_one), "m.onnx").ok());
  EXPECT_TRUE(CheckOnnxGraph(conv(other), "m.onnx").ok());  // pads may be 0
  EXPECT_EQ(CheckOnnxGraph(conv(group_zero), "m.onnx").message(),
            "m.onnx: ONNX node 0 (Conv): attribute 'group' is 0 (must be from 1 to 2^20)");
  EXPECT_THAT(CheckOnnxGraph(conv(packed_strides), "m.onnx").message(),
              HasSubstr("attribute 'strides' is 0"));
}

TEST(OnnxGraphCheck, AcceptsTheDefaultDetector) {
  const Result<std::string> bytes =
      ReadFile(std::filesystem::path(SEMCHAIN_SOURCE_DIR) / "models/detector.onnx");
  ASSERT_TRUE(bytes.ok()) << bytes.status().message();
  const Status status = CheckOnnxGraph(*bytes, "detector.onnx");
  EXPECT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(OnnxStaticInputSize(*bytes), std::make_optional(std::pair(320, 256)));
}

}  // namespace
}  // namespace semchain::detection
