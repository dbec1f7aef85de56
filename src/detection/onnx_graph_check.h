#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "core/status.h"

// A check of an ONNX model's graph before OpenCV reads it: OpenCV 4.6's ONNX importer
// dereferences null on some malformed models (found by fuzz/onnx_model_fuzzer.cc: a node whose
// input no earlier node, graph input or initializer produces) instead of throwing.
namespace semchain::detection {

// Walks the protobuf wire format of an onnx.ModelProto (onnx/onnx.proto3: ModelProto.graph = 7;
// GraphProto.node = 1, initializer = 5, input = 11, output = 12, sparse_initializer = 15;
// NodeProto.input = 1, output = 2, op_type = 4; TensorProto.name = 8; ValueInfoProto.name = 1;
// SparseTensorProto.values = 1) and fails, naming 'source', when the bytes are not well-formed
// protobuf, there is no graph, or the graph is not topologically sorted (the rule of ONNX's own
// checker: every node input is a graph input, an initializer or an output of an earlier node,
// and every graph output is produced). Subgraphs of control-flow nodes are not descended into.
Status CheckOnnxGraph(std::string_view bytes, const std::string& source);

// The (width, height) of the model's image input when its shape is static: the first graph
// input that is not an initializer, of rank 4 (NCHW) with fixed positive H and W
// (ValueInfoProto.type = 2 → TypeProto.tensor_type = 1 → shape = 2 → dim = 1 → dim_value = 1).
// nullopt for a dynamic or unreadable shape.
std::optional<std::pair<int, int>> OnnxStaticInputSize(std::string_view bytes);

}  // namespace semchain::detection
