#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <opencv2/dnn.hpp>
#include <optional>
#include <string>
#include <vector>

#include "detection/class_map.h"
#include "detection/detector.h"
#include "detection/yolo_head.h"

// A YOLOv8-format ONNX detector run through OpenCV DNN (DESIGN.md §3.10): letterbox, 1/255
// scaling, the raw head (DFL decoded here) or the decoded head, confidence threshold, the class
// map if one is given, class-wise NMS, boxes mapped back to the image. The model is read as
// onnx_model_prepare.h says: ultralytics' default export (decoded head, also in half precision)
// is cut at its raw head in memory and runs as it is.
namespace semchain::detection {

struct YoloOptions {
  // The network input in pixels, both multiples of 32 (the largest stride), or both 0: the
  // model's own, read from its ONNX graph when the export has a static shape (what OpenCV
  // needs), else 640 × 640. A static model asked for another size is an error at Load.
  int input_width = 0;
  int input_height = 0;
  // Detections scoring below this are dropped (ultralytics' predict default).
  double confidence_threshold = 0.25;
  // Same-class boxes overlapping a better one by more than this IoU are dropped (OpenCV's and
  // YOLOv5's usual value; ultralytics' predict uses 0.7, which keeps more near-duplicates).
  double nms_iou_threshold = 0.45;
  // At most this many detections per image, best first.
  int max_detections = 300;

  bool Validate(std::string* error) const;
  cv::Size input_size() const { return {input_width, input_height}; }
};

// Sets options->input_width and input_height from "WIDTHxHEIGHT" or "auto" (0 × 0: the
// model's own), the CLI's --input.
Status ParseInputSize(const std::string& text, YoloOptions* options);

class YoloDetector final : public Detector {
 public:
  // Loads 'model_path' with the class names 'class_names' (class-id order; empty: the names in
  // the model's metadata, as ultralytics' exporter writes them) and runs it once on a grey input
  // so that a model OpenCV cannot run, an output of the wrong shape or a class-count mismatch
  // is reported here, once, with the model's path in front. With a 'class_map' file
  // (class_map.h) the detections are of semchain's classes, mapped from the model's.
  static Result<std::unique_ptr<YoloDetector>> Load(const std::filesystem::path& model_path,
                                                    std::vector<std::string> class_names,
                                                    const YoloOptions& options,
                                                    const std::filesystem::path& class_map = {});

  Result<std::vector<Detection>> Detect(const cv::Mat& rgb) override;

  // What the model costs at its input size, as OpenCV counts its graph: floating-point
  // operations of one forward pass and the weights' element count.
  struct Cost {
    double gflops = 0.0;
    std::int64_t parameters = 0;
  };
  Cost ModelCost();
  // The classes of the detections: the model's, or semchain's with a class map.
  const std::vector<std::string>& class_names() const override { return class_names_; }
  // The model's own classes (class_names() without a class map).
  const std::vector<std::string>& model_class_names() const { return model_class_names_; }
  const HeadLayout& head() const { return head_; }
  // True when the model's graph went on after its raw head (ultralytics' default export) and
  // was cut there (onnx_model_prepare.h).
  bool decoding_removed() const { return decoding_removed_; }
  // With the input size resolved (never 0 × 0).
  const YoloOptions& options() const { return options_; }

 private:
  YoloDetector(cv::dnn::Net net, std::vector<std::string> class_names, const YoloOptions& options)
      : net_(std::move(net)), class_names_(std::move(class_names)), options_(options) {}

  // The network's output for a letterboxed RGB input (CV_8UC3 of the input size).
  Result<cv::Mat> Forward(const cv::Mat& input_rgb);

  cv::dnn::Net net_;
  std::vector<std::string> class_names_;
  std::vector<std::string> model_class_names_;
  std::optional<ClassMap> class_map_;
  YoloOptions options_;
  HeadLayout head_;
  std::vector<Anchor> anchors_;
  bool decoding_removed_ = false;
};

// An error naming 'model_path' when it is not a readable file ("M.onnx: no such model file").
Status CheckModelFile(const std::filesystem::path& model_path);

// The class names of 'model_path': read from 'classes_path' when it is not empty, else from
// the file beside the model with the same stem and the extension ".names" (DESIGN.md §5.5).
Result<std::vector<std::string>> LoadModelClassNames(const std::filesystem::path& model_path,
                                                     const std::filesystem::path& classes_path);

// What `--model M.onnx [--classes FILE] [--class-map FILE]` means: CheckModelFile, the class
// names (LoadModelClassNames when 'classes_path' is given or M.names exists, else the model's
// metadata), then YoloDetector::Load; the first error is returned.
Result<std::unique_ptr<YoloDetector>> LoadYoloDetector(const std::filesystem::path& model_path,
                                                       const std::filesystem::path& classes_path,
                                                       const YoloOptions& options,
                                                       const std::filesystem::path& class_map = {});

}  // namespace semchain::detection
