// semchain detect [--model M.onnx] --images DIR|IMAGE --out DIR [--classes F] [--conf T] [--nms T]
//                 [--input WxH] [--class-map F]
// Runs a YOLOv8-format ONNX detector (DESIGN.md §3.10) on images or on a run directory's
// frames: writes DIR/detections.jsonl (§5.5) and DIR/annotated/<frame>.png. On a run directory
// (camera.yaml + frames/) detections get depth_m from the aligned depth frames and frame names
// like the simulator's ("frames/000123").
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <opencv2/core/utils/logger.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "apps/command.h"
#include "apps/shipped_file.h"
#include "core/atomic_file.h"
#include "core/progress_bar.h"
#include "detection/detection_drawing.h"
#include "detection/run_detection.h"
#include "detection/yolo_detector.h"
#include "io/detections_io.h"
#include "io/rgbd_frame_io.h"

namespace semchain::app {
namespace {

namespace fs = std::filesystem;

struct DetectArgs {
  std::string model;
  std::string images;
  std::string out;
  std::string classes;
  std::string class_map;       // the model's classes mapped to semchain's (detection/class_map.h)
  std::string input = "auto";  // the model's own (a static export's size), else 640x640
  double confidence = detection::YoloOptions().confidence_threshold;
  double nms = detection::YoloOptions().nms_iou_threshold;
};

Result<detection::YoloOptions> BuildOptions(const DetectArgs& args) {
  detection::YoloOptions options;
  SEMCHAIN_RETURN_IF_ERROR(detection::ParseInputSize(args.input, &options));
  options.confidence_threshold = args.confidence;
  options.nms_iou_threshold = args.nms;
  std::string error;
  if (!options.Validate(&error)) return Status::Error("invalid detector options: " + error);
  return options;
}

bool IsImageFile(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return extension == ".png" || extension == ".jpg" || extension == ".jpeg" || extension == ".bmp";
}

// The images to run on: the file itself, or a directory's image files in name order.
Result<std::vector<fs::path>> ListImages(const fs::path& images) {
  std::error_code ec;
  if (fs::is_regular_file(images, ec)) return std::vector<fs::path>{images};
  if (!fs::is_directory(images, ec)) {
    return Status::Error(images.string() + ": no such image file or directory");
  }
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(images, ec)) {
    if (entry.is_regular_file() && IsImageFile(entry.path())) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    return Status::Error(images.string() +
                         ": no images (.png, .jpg, .bmp) and not a run directory (camera.yaml + "
                         "frames/)");
  }
  return files;
}

Status WriteAnnotated(const fs::path& out, const std::string& frame, const cv::Mat& rgb,
                      const std::vector<Detection>& detections) {
  const fs::path path = out / "annotated" / (frame + ".png");
  SEMCHAIN_RETURN_IF_ERROR(EnsureWritableDirectory(path.parent_path()));
  cv::Mat bgr;
  cv::cvtColor(detection::DrawDetections(rgb, detections), bgr, cv::COLOR_RGB2BGR);
  std::vector<unsigned char> bytes;
  if (!cv::imencode(".png", bgr, bytes)) return Status::Error(path.string() + ": cannot encode");
  return WriteFileAtomically(
      path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

// Plain images have no clock: the stamp is the image's position in name order.
Result<std::vector<FrameDetections>> DetectImages(detection::Detector& detector,
                                                  const std::vector<fs::path>& images,
                                                  const fs::path& out) {
  std::vector<FrameDetections> frames;
  ProgressBar bar("detect", images.size());
  for (const fs::path& image : images) {
    Result<cv::Mat> rgb = ReadColorImage(image);
    if (!rgb.ok()) return rgb.status();
    Result<std::vector<Detection>> found = detector.Detect(*rgb);
    if (!found.ok()) return found.status().WithContext(image.string());
    FrameDetections frame{image.stem().string(), double(frames.size()), std::move(*found)};
    SEMCHAIN_RETURN_IF_ERROR(WriteAnnotated(out, frame.frame, *rgb, frame.detections));
    frames.push_back(std::move(frame));
    bar.Update(frames.size());
  }
  bar.Finish();
  return frames;
}

Status RunDetect(const DetectArgs& args) {
  Result<detection::YoloOptions> options = BuildOptions(args);
  if (!options.ok()) return options.status();
  Result<std::unique_ptr<detection::YoloDetector>> detector =
      detection::LoadYoloDetector(args.model, args.classes, *options, args.class_map);
  if (!detector.ok()) return detector.status();
  const fs::path images(args.images), out(args.out);
  const bool run = detection::IsRunDirectory(images);
  std::vector<fs::path> files;
  if (!run) {
    Result<std::vector<fs::path>> listed = ListImages(images);
    if (!listed.ok()) return listed.status();
    files = std::move(*listed);
  }
  std::error_code ec;
  if (run && fs::exists(out, ec) && fs::equivalent(images, out, ec)) {
    return Status::Error(args.out + ": --out must not be the run directory itself (its " +
                         "detections.jsonl is the simulator's record)");
  }
  SEMCHAIN_RETURN_IF_ERROR(EnsureWritableDirectory(out));
  Result<std::vector<FrameDetections>> frames = std::vector<FrameDetections>();
  if (run) {
    detection::RunDetectionOptions run_options;
    run_options.show_progress = true;
    frames = detection::DetectRunFrames(
        **detector, images, run_options, [&out](const cv::Mat& rgb, const FrameDetections& frame) {
          return WriteAnnotated(out, frame.frame, rgb, frame.detections);
        });
  } else {
    frames = DetectImages(**detector, files, out);
  }
  if (!frames.ok()) return frames.status();
  SEMCHAIN_RETURN_IF_ERROR(WriteDetectionsJsonl(out / "detections.jsonl", *frames));
  std::size_t count = 0;
  for (const FrameDetections& frame : *frames) count += frame.detections.size();
  const char* head = (*detector)->head().kind == detection::HeadKind::kDecoded ? "decoded head"
                     : (*detector)->decoding_removed() ? "raw head, the model's decoding cut"
                                                       : "raw head";
  spdlog::info("detect: {} detections in {} frames ({}) -> {}", count, frames->size(), head,
               (out / "detections.jsonl").string());
  return Status::Ok();
}

}  // namespace

void AddDetectCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<DetectArgs>();
  CLI::App* command =
      app.add_subcommand("detect",
                         "Run a YOLOv8-format ONNX detector on images or a run directory's frames: "
                         "detections.jsonl and annotated PNGs");
  // Not given: the shipped detector, found as a given path is (force_callback runs the transform
  // on the default).
  command->add_option("--model", args->model, "ONNX model (raw or decoded YOLOv8 head)")
      ->transform(ShippedFile())
      ->default_str(kDefaultDetector)
      ->force_callback();
  command
      ->add_option("--images", args->images,
                   "An image, a folder of images, or a run directory (camera.yaml + frames/: "
                   "depths from its depth frames)")
      ->required();
  command->add_option("--out", args->out, "Output folder: detections.jsonl, annotated/")
      ->required();
  command
      ->add_option("--classes", args->classes,
                   "Class names, one per line (default: the model's .names file)")
      ->transform(ShippedFile());
  command->add_option("--class-map", args->class_map,
                      "YAML map 'model class: semchain class' (e.g. config/classes/coco.yaml): "
                      "detections of semchain's classes; the classes it does not name are dropped");
  command->add_option("--conf", args->confidence, "Confidence threshold")->capture_default_str();
  command->add_option("--nms", args->nms, "NMS IoU threshold (per class)")->capture_default_str();
  command
      ->add_option("--input", args->input,
                   "Network input WIDTHxHEIGHT (multiples of 32), or auto: the model's export size")
      ->capture_default_str();
  command->callback([args, &exit_code] {
    // OpenCV logs its own diagnostics on stderr; the error line below says what went wrong.
    cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
    const Status status = RunDetect(*args);
    exit_code = status.ok() ? 0 : ReportError(status);
  });
}

}  // namespace semchain::app
