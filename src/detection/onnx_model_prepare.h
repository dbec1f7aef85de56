#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/status.h"

// What semchain does to a YOLOv8 ONNX model before OpenCV 4.6 DNN reads it, so that the model
// ultralytics exports by default (`yolo export format=onnx`, also with half=True) runs as it is:
// no re-export, no Python. The model is parsed with Debian's ONNX library (onnx::ModelProto) and
// rewritten in memory (onnx_rewrite.h, onnx_raw_head.h):
//   1. FLOAT16 weights, constants and types become FLOAT (OpenCV 4.6 refuses FLOAT16);
//   2. Split sizes given as an input become the attribute OpenCV 4.6 reads;
//   3. the graph is cut at the YOLOv8 raw head (1 × (64 + nc) × N) when it goes on after it:
//      ultralytics' box decoding (DFL softmax and convolution, anchors, Sigmoid), which OpenCV
//      4.6 cannot import, is dropped, and semchain decodes the raw head itself (yolo_head.h).
// The file on disk is never changed.
namespace semchain::detection {

struct PreparedOnnxModel {
  std::string bytes;  // the serialized model for cv::dnn::readNetFromONNX(buffer, size)
  // The class count of the raw head found in the graph; nullopt when none was found (the model
  // is then handed to OpenCV with only steps 1 and 2 applied, as a hand-made model is).
  std::optional<int> head_classes;
  int head_strides = 0;           // the levels the found head concatenates
  bool decoding_removed = false;  // the graph went on after the raw head (step 3 cut it)
  int float16_tensors = 0;        // tensors and types converted by step 1
  int split_nodes = 0;            // nodes changed by step 2
  // The class names of metadata_props "names" (ultralytics' exporter writes them); empty when
  // the model has none. 'names_error' says why they could not be read when it has.
  std::vector<std::string> class_names;
  std::string names_error;
};

// Parses and rewrites 'bytes', an ONNX model that CheckOnnxGraph accepted; the error names
// 'source' ("M.onnx: not an ONNX model ...").
Result<PreparedOnnxModel> PrepareOnnxModel(std::string_view bytes, const std::string& source);

}  // namespace semchain::detection
