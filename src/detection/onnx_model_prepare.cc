#include "detection/onnx_model_prepare.h"

#include <onnx/onnx_pb.h>

#include <limits>

#include "detection/onnx_graph_check.h"
#include "detection/onnx_raw_head.h"
#include "detection/onnx_rewrite.h"
#include "detection/ultralytics_names.h"

namespace semchain::detection {
namespace {

void ReadMetadataNames(const onnx::ModelProto& model, PreparedOnnxModel* prepared) {
  for (const onnx::StringStringEntryProto& entry : model.metadata_props()) {
    if (entry.key() != "names") continue;
    Result<std::vector<std::string>> names = ParseUltralyticsNames(entry.value());
    if (names.ok()) {
      prepared->class_names = std::move(*names);
      prepared->names_error.clear();
    } else {
      prepared->class_names.clear();
      prepared->names_error = "metadata 'names': " + names.status().message();
    }
  }
}

}  // namespace

Result<PreparedOnnxModel> PrepareOnnxModel(std::string_view bytes, const std::string& source) {
  onnx::ModelProto model;
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()) ||
      !model.ParseFromArray(bytes.data(), static_cast<int>(bytes.size()))) {
    return Status::Error(source + ": not an ONNX model (malformed protobuf)");
  }
  PreparedOnnxModel prepared;
  ReadMetadataNames(model, &prepared);
  prepared.float16_tensors = ConvertFloat16ToFloat(&model);
  prepared.split_nodes = MoveSplitSizesToAttributes(model.mutable_graph());
  if (const std::optional<RawHeadInGraph> head = FindRawHead(model.graph())) {
    prepared.head_classes = head->classes;
    prepared.head_strides = head->strides;
    prepared.decoding_removed = CutAtRawHead(model.mutable_graph(), *head);
  }
  if (prepared.float16_tensors == 0 && prepared.split_nodes == 0 && !prepared.decoding_removed) {
    prepared.bytes.assign(bytes);  // nothing rewritten: OpenCV reads the file's own bytes
    return prepared;
  }
  if (!model.SerializeToString(&prepared.bytes)) {
    return Status::Error(source + ": cannot serialize the rewritten ONNX model");
  }
  // The rewritten graph must still be one OpenCV can be given safely.
  const Status check = CheckOnnxGraph(prepared.bytes, source + " (rewritten)");
  if (!check.ok()) return check;
  return prepared;
}

}  // namespace semchain::detection
