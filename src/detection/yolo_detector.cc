#include "detection/yolo_detector.h"

#include <algorithm>
#include <opencv2/dnn/shape_utils.hpp>
#include <optional>
#include <regex>
#include <system_error>
#include <utility>

#include "core/atomic_file.h"
#include "detection/class_nms.h"
#include "detection/letterbox.h"
#include "detection/onnx_graph_check.h"
#include "detection/onnx_model_prepare.h"
#include "io/detections_io.h"

namespace semchain::detection {

Status ParseInputSize(const std::string& text, YoloOptions* options) {
  if (text == "auto") {
    options->input_width = options->input_height = 0;
    return Status::Ok();
  }
  std::smatch match;
  if (!std::regex_match(text, match, std::regex(R"((\d{1,5})x(\d{1,5}))"))) {
    return Status::Error("--input " + text + ": expected WIDTHxHEIGHT, e.g. 640x640, or auto");
  }
  options->input_width = std::stoi(match[1]);
  options->input_height = std::stoi(match[2]);
  return Status::Ok();
}
namespace fs = std::filesystem;
namespace {

// OpenCV's message without its file, line and function decoration, on one line.
std::string OpenCvMessage(const cv::Exception& error) {
  std::string message = error.err.empty() ? error.what() : error.err;
  std::replace(message.begin(), message.end(), '\n', ' ');
  return message;
}

struct LoadedNet {
  cv::dnn::Net net;
  PreparedOnnxModel prepared;  // without its bytes
};

// What OpenCV's error means for the model as semchain prepared it.
std::string CannotLoad(const fs::path& model_path, const PreparedOnnxModel& prepared) {
  if (prepared.head_classes) {
    return model_path.string() + ": OpenCV DNN cannot load this ONNX model (cut at its raw head)";
  }
  return model_path.string() +
         ": OpenCV DNN cannot load this ONNX model, and its graph has no YOLOv8 raw head to cut "
         "it at (per stride a Concat of a 64-channel box and an nc-channel class convolution; "
         "see the README, \"Bring your own detector\")";
}

// The model's network and the input size to run it at: 'options''s, or the model's own for 0 × 0.
// A static export asked for another size is tried at that size (a graph in which nothing depends
// on the size runs at any); 'exported_size' gets the export's size for the error when it does not.
Result<LoadedNet> ReadNet(const fs::path& model_path, YoloOptions* options,
                          std::optional<std::pair<int, int>>* exported_size) {
  SEMCHAIN_RETURN_IF_ERROR(CheckModelFile(model_path));
  const Result<std::string> bytes = ReadFile(model_path);
  if (!bytes.ok()) return bytes.status();
  SEMCHAIN_RETURN_IF_ERROR(CheckOnnxGraph(*bytes, model_path.string()));
  const std::optional<std::pair<int, int>> exported = OnnxStaticInputSize(*bytes);
  *exported_size = exported;
  if (options->input_width == 0 && options->input_height == 0) {
    constexpr int kDynamicDefault = 640;  // ultralytics' export and predict default
    options->input_width = exported ? exported->first : kDynamicDefault;
    options->input_height = exported ? exported->second : kDynamicDefault;
    std::string invalid;
    if (!options->Validate(&invalid)) return Status::Error(model_path.string() + ": " + invalid);
  }
  Result<PreparedOnnxModel> prepared = PrepareOnnxModel(*bytes, model_path.string());
  if (!prepared.ok()) return prepared.status();
  LoadedNet loaded;
  try {
    loaded.net = cv::dnn::readNetFromONNX(prepared->bytes.data(), prepared->bytes.size());
  } catch (const cv::Exception& error) {
    return Status::Error(CannotLoad(model_path, *prepared) + ": " + OpenCvMessage(error));
  } catch (const std::exception& error) {
    return Status::Error(CannotLoad(model_path, *prepared) + ": " + error.what());
  }
  if (loaded.net.empty()) {
    return Status::Error(model_path.string() + ": OpenCV read an empty network");
  }
  loaded.net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  loaded.net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  prepared->bytes.clear();
  loaded.prepared = std::move(*prepared);
  return loaded;
}

// 'class_names', or when empty the model's metadata names; a head whose class count the graph
// shows must have as many.
Result<std::vector<std::string>> ResolveClassNames(const fs::path& model_path,
                                                   std::vector<std::string> class_names,
                                                   const PreparedOnnxModel& prepared) {
  if (class_names.empty()) {
    if (!prepared.names_error.empty()) {
      return Status::Error(model_path.string() + ": " + prepared.names_error);
    }
    if (prepared.class_names.empty()) {
      return Status::Error(model_path.string() +
                           ": no class names (no .names file beside the model, no --classes "
                           "FILE, and no 'names' in the model's metadata)");
    }
    class_names = prepared.class_names;
  }
  if (prepared.head_classes && *prepared.head_classes != static_cast<int>(class_names.size())) {
    return Status::Error(model_path.string() + ": class-count mismatch: the model's head has " +
                         std::to_string(*prepared.head_classes) + " classes, but there are " +
                         std::to_string(class_names.size()) + " class names");
  }
  return class_names;
}

}  // namespace

bool YoloOptions::Validate(std::string* error) const {
  const bool from_model = input_width == 0 && input_height == 0;
  if (!from_model &&
      (input_width <= 0 || input_height <= 0 || input_width % 32 != 0 || input_height % 32 != 0)) {
    *error = "input size " + std::to_string(input_width) + "x" + std::to_string(input_height) +
             ": width and height must be positive multiples of 32 (or both 0: the model's own)";
    return false;
  }
  if (!(confidence_threshold > 0.0 && confidence_threshold <= 1.0)) {
    *error = "confidence threshold must be in (0, 1]";
    return false;
  }
  if (!(nms_iou_threshold > 0.0 && nms_iou_threshold <= 1.0)) {
    *error = "NMS IoU threshold must be in (0, 1]";
    return false;
  }
  if (max_detections <= 0) {
    *error = "max_detections must be positive";
    return false;
  }
  return true;
}

Result<std::unique_ptr<YoloDetector>> YoloDetector::Load(const fs::path& model_path,
                                                         std::vector<std::string> class_names,
                                                         const YoloOptions& options,
                                                         const fs::path& class_map) {
  std::string error;
  if (!options.Validate(&error)) return Status::Error(error);
  YoloOptions resolved = options;
  std::optional<std::pair<int, int>> exported;
  Result<LoadedNet> loaded = ReadNet(model_path, &resolved, &exported);
  if (!loaded.ok()) return loaded.status();
  Result<std::vector<std::string>> names =
      ResolveClassNames(model_path, std::move(class_names), loaded->prepared);
  if (!names.ok()) return names.status();
  std::unique_ptr<YoloDetector> detector(
      new YoloDetector(std::move(loaded->net), *names, resolved));
  detector->model_class_names_ = std::move(*names);
  detector->decoding_removed_ = loaded->prepared.decoding_removed;
  const cv::Mat grey(resolved.input_size(), CV_8UC3, cv::Scalar::all(kLetterboxGrey));
  Result<cv::Mat> output = detector->Forward(grey);
  if (!output.ok() && exported &&
      *exported != std::pair(resolved.input_width, resolved.input_height)) {
    return Status::Error(model_path.string() + ": " + output.status().message() +
                         " (the model was exported for a " + std::to_string(exported->first) + "x" +
                         std::to_string(exported->second) + " input: give that size or auto)");
  }
  if (!output.ok()) return output.status().WithContext(model_path.string());
  Result<HeadLayout> head =
      IdentifyHead(*output, int(detector->model_class_names_.size()), resolved.input_size());
  if (!head.ok()) return head.status().WithContext(model_path.string());
  detector->head_ = *head;
  detector->anchors_ = MakeAnchors(resolved.input_size());
  if (!class_map.empty()) {
    Result<ClassMap> map = LoadClassMap(class_map, detector->model_class_names_);
    if (!map.ok()) return map.status();
    detector->class_names_ = map->classes;
    detector->class_map_ = std::move(*map);
  }
  return detector;
}

Result<cv::Mat> YoloDetector::Forward(const cv::Mat& input_rgb) {
  // The image is already RGB (what YOLOv8 was trained on): no channel swap here.
  const cv::Mat blob = cv::dnn::blobFromImage(input_rgb, 1.0 / 255.0, cv::Size(), cv::Scalar(),
                                              /*swapRB=*/false, /*crop=*/false, CV_32F);
  try {
    net_.setInput(blob);
    cv::Mat output = net_.forward();
    return output.isContinuous() ? output : output.clone();
  } catch (const cv::Exception& error) {
    return Status::Error("OpenCV DNN cannot run the model at " + std::to_string(input_rgb.cols) +
                         "x" + std::to_string(input_rgb.rows) + ": " + OpenCvMessage(error));
  } catch (const std::exception& error) {
    return Status::Error("OpenCV DNN cannot run the model: " + std::string(error.what()));
  }
}

YoloDetector::Cost YoloDetector::ModelCost() {
  Cost cost;
  const cv::dnn::MatShape input = {1, 3, options_.input_height, options_.input_width};
  std::int64_t flops = 0;
  for (const std::string& name : net_.getLayerNames()) {
    const int id = net_.getLayerId(name);
    const cv::Ptr<cv::dnn::Layer> layer = net_.getLayer(id);
    for (const cv::Mat& blob : layer->blobs) {
      cost.parameters += static_cast<std::int64_t>(blob.total());
    }
    if (layer->type == "InnerProduct" && layer->blobs.empty()) {
      // A MatMul of two computed tensors (attention). OpenCV 4.6 counts an InnerProduct's FLOPs
      // from its weights' shape, which this one does not have (it would read past an empty
      // vector and crash): 2·K multiply-adds per output value, K the shared dimension.
      std::vector<cv::dnn::MatShape> in, out;
      net_.getLayerShapes(input, id, in, out);
      if (!in.empty() && !in[0].empty() && !out.empty()) {
        flops += 2 * static_cast<std::int64_t>(in[0].back()) *
                 static_cast<std::int64_t>(cv::dnn::total(out[0]));
      }
      continue;
    }
    flops += net_.getFLOPS(id, input);
  }
  cost.gflops = static_cast<double>(flops) * 1e-9;
  return cost;
}

Result<std::vector<Detection>> YoloDetector::Detect(const cv::Mat& rgb) {
  if (rgb.empty() || rgb.type() != CV_8UC3) {
    return Status::Error("the detector needs a non-empty 8-bit 3-channel RGB image");
  }
  const Letterbox letterbox = FitLetterbox(rgb.size(), options_.input_size());
  Result<cv::Mat> output = Forward(ApplyLetterbox(rgb, letterbox));
  if (!output.ok()) return output.status();
  Result<HeadLayout> head = IdentifyHead(*output, head_.classes, options_.input_size());
  if (!head.ok()) return head.status();
  std::vector<Candidate> candidates =
      DecodeHead(*output, *head, anchors_, options_.confidence_threshold);
  if (class_map_) candidates = MapCandidates(std::move(candidates), *class_map_);
  std::vector<Detection> detections;
  const double limits[4] = {double(rgb.cols), double(rgb.rows), double(rgb.cols), double(rgb.rows)};
  for (int index : ClassWiseNms(candidates, options_.nms_iou_threshold, options_.max_detections)) {
    const Candidate& candidate = candidates[index];
    const cv::Point2d top_left = letterbox.ToImage(candidate.box.tl());
    const cv::Point2d bottom_right = letterbox.ToImage(candidate.box.br());
    Detection detection;
    detection.class_id = candidate.class_id;
    detection.class_name = class_names_[candidate.class_id];
    detection.score = std::clamp(double(candidate.score), 0.0, 1.0);
    const double corners[4] = {top_left.x, top_left.y, bottom_right.x, bottom_right.y};
    for (int i = 0; i < 4; ++i) detection.box[i] = std::clamp(corners[i], 0.0, limits[i]);
    if (detection.box[2] <= detection.box[0] || detection.box[3] <= detection.box[1]) continue;
    detections.push_back(std::move(detection));
  }
  return detections;
}

Status CheckModelFile(const fs::path& model_path) {
  std::error_code ec;
  if (!fs::is_regular_file(model_path, ec)) {
    return Status::Error(model_path.string() + ": no such model file");
  }
  return Status::Ok();
}

Result<std::vector<std::string>> LoadModelClassNames(const fs::path& model_path,
                                                     const fs::path& classes_path) {
  fs::path path = classes_path;
  if (path.empty()) {
    path = model_path;
    path.replace_extension(".names");
  }
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    return Status::Error(path.string() + ": no class-names file (one name per line, beside " +
                         "the model with the same stem, or --classes FILE)");
  }
  Result<std::vector<std::string>> names = ReadClassNames(path);
  if (names.ok() && names->empty()) return Status::Error(path.string() + ": no class names");
  return names;
}

Result<std::unique_ptr<YoloDetector>> LoadYoloDetector(const fs::path& model_path,
                                                       const fs::path& classes_path,
                                                       const YoloOptions& options,
                                                       const fs::path& class_map) {
  SEMCHAIN_RETURN_IF_ERROR(CheckModelFile(model_path));
  fs::path beside = model_path;
  beside.replace_extension(".names");
  std::error_code ec;
  std::vector<std::string> names;  // empty: the model's metadata names
  if (!classes_path.empty() || fs::exists(beside, ec)) {
    Result<std::vector<std::string>> read = LoadModelClassNames(model_path, classes_path);
    if (!read.ok()) return read.status();
    names = std::move(*read);
  }
  return YoloDetector::Load(model_path, std::move(names), options, class_map);
}

}  // namespace semchain::detection
