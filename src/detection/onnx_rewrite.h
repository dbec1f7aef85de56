#pragma once

#include <onnx/onnx_pb.h>

#include <cstdint>
#include <string>
#include <vector>

// Rewrites of an ONNX model (Debian's libonnx-dev, onnx::ModelProto) that let OpenCV 4.6's
// importer read what current exporters write. Each keeps what the graph computes.
namespace semchain::detection {

// The constant tensor 'name' of 'graph': an initializer or the 'value' of a Constant node;
// null when 'name' is computed, a graph input, or absent.
const onnx::TensorProto* FindConstantTensor(const onnx::GraphProto& graph, const std::string& name);

// The values of an INT64 or INT32 constant tensor; false when it is neither or is malformed.
bool ReadIntegers(const onnx::TensorProto& tensor, std::vector<std::int64_t>* values);

// Half precision as a `half=True` export writes it, which OpenCV 4.6 refuses ("Unsupported data
// type: FLOAT16"), made single precision: FLOAT16 initializers and tensor attributes (Constant
// values) are converted to FLOAT, FLOAT16 graph inputs, outputs and value_info become FLOAT, and
// Cast nodes to FLOAT16 cast to FLOAT. A Cast to FLOAT of a tensor that is then already FLOAT
// (onnx shape inference gives the types) is removed and its readers read its input. Returns the
// number of tensors and tensor types converted (Casts not counted).
int ConvertFloat16ToFloat(onnx::ModelProto* model);

// Split nodes whose sizes are their second input (opset 13 and later: what torch writes for
// ultralytics' C2f split() and for Detect's split of the box and class rows) get them as the
// 'split' attribute instead: OpenCV 4.6 ignores the input and splits into equal parts. Only
// constant sizes are moved. Returns the number of nodes changed.
int MoveSplitSizesToAttributes(onnx::GraphProto* graph);

}  // namespace semchain::detection
