#pragma once

#include <onnx/onnx_pb.h>

#include <optional>
#include <string>

// The raw head of a YOLOv8 detection model inside its ONNX graph (yolo_head.h: 1 × (64 + nc) × N,
// per anchor 4 × 16 DFL logits, then nc class logits), found by the structure ultralytics'
// Detect head exports, wherever the graph goes on after it (ultralytics' default export decodes
// the boxes there, which OpenCV 4.6 cannot import):
//   joined    per stride, a Concat on the channels of the 64-channel box Conv and the nc-channel
//             class Conv, each reshaped to (1, 64 + nc, H·W), concatenated over the strides on
//             the anchors (ultralytics 8.0 to 8.3: the tensor Detect's decoding splits);
//   separate  the 64-channel box Convs reshaped and concatenated over the strides, and likewise
//             the nc-channel class Convs, whose result the graph passes through a Sigmoid (later
//             ultralytics versions): the raw head is their Concat on the channels.
namespace semchain::detection {

struct RawHeadInGraph {
  // joined: the raw head tensor; separate: the box (64 × N) and class (nc × N) tensors.
  std::string tensor;
  std::string class_tensor;  // empty when joined
  int classes = 0;
  int strides = 0;  // the levels concatenated (3 for strides 8, 16, 32)
};

// The raw head the graph's first output is computed from, the first in node order when there
// are several; nullopt when there is none (a hand-made model, or another architecture).
std::optional<RawHeadInGraph> FindRawHead(const onnx::GraphProto& graph);

// Makes the raw head the graph's only output (FLOAT, 1 × (64 + nc) × anchors; for a separate
// head a Concat node "semchain_raw_head" is added) and drops the nodes, initializers and
// value_info the head does not need. Returns false when the head already was the only output
// (nothing to cut), true when nodes after it were dropped.
bool CutAtRawHead(onnx::GraphProto* graph, const RawHeadInGraph& head);

}  // namespace semchain::detection
