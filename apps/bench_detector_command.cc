// semchain bench detector --model M.onnx --data DATA/data.yaml [--split test] [--input WxH]
//                         [--threads 2] [--confusion-conf 0.25] --out DIR
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>

#include "apps/command.h"
#include "apps/shipped_file.h"
#include "core/atomic_file.h"
#include "core/progress_bar.h"
#include "detection/detector_benchmark.h"
#include "detection/yolo_detector.h"

namespace semchain::app {
namespace {
namespace fs = std::filesystem;

struct BenchDetectorArgs {
  std::string model;
  std::string classes;
  std::string class_map;  // the model's classes mapped to semchain's (detection/class_map.h)
  std::string data;
  std::string split = "test";
  std::string input = "auto";  // the model's own (a static export's size), else 640x640
  int threads = 2;
  double confusion_conf = 0.25;
  std::string out;
};

std::string Markdown(const nlohmann::json& r, const std::vector<std::string>& names) {
  char line[512];
  std::string md = "# Detector benchmark\n\n";
  std::snprintf(line, sizeof(line),
                "Model `%s` on `%s` (%s split, %d images, %d objects), input %s, %d threads.\n\n",
                r["model"].get<std::string>().c_str(), r["data"].get<std::string>().c_str(),
                r["split"].get<std::string>().c_str(), r["images"].get<int>(),
                r["objects"].get<int>(), r["input"].get<std::string>().c_str(),
                r["threads"].get<int>());
  md += line;
  md +=
      "| mAP@0.5 | mAP@0.5:0.95 | precision | recall | ms / frame (mean, median) | GFLOPs | "
      "parameters | MB |\n|---|---|---|---|---|---|---|---|\n";
  std::snprintf(line, sizeof(line),
                "| %.3f | %.3f | %.3f | %.3f | %.1f, %.1f | %.2f | %.2f M | %.1f |\n\n",
                r["map50"].get<double>(), r["map50_95"].get<double>(), r["precision"].get<double>(),
                r["recall"].get<double>(), r["ms_per_frame"].get<double>(),
                r["median_ms_per_frame"].get<double>(), r["gflops"].get<double>(),
                r["parameters"].get<double>() * 1e-6, r["file_mb"].get<double>());
  md += line;
  md += "| class | objects | AP@0.5 | AP@0.5:0.95 |\n|---|---|---|---|\n";
  for (const std::string& name : names) {
    const nlohmann::json& c = r["classes"][name];
    std::snprintf(line, sizeof(line), "| %s | %d | %.3f | %.3f |\n", name.c_str(),
                  c["objects"].get<int>(), c["ap50"].get<double>(), c["ap50_95"].get<double>());
    md += line;
  }
  std::snprintf(line, sizeof(line),
                "\nWhat the detector named each labelled object (rows; detections at confidence "
                "%.2f or more paired one to one at IoU 0.45 or more, whatever their class); the "
                "last row: detections on no labelled object.\n\n| object \\ named |",
                r["confusion_conf"].get<double>());
  md += line;
  for (const std::string& name : names) md += " " + name + " |";
  md += " missed |\n|---|";
  for (std::size_t k = 0; k <= names.size(); ++k) md += "---|";
  md += "\n";
  const nlohmann::json& confusion = r["confusion"];
  for (const std::string& row : names) {
    md += "| " + row + " |";
    for (const std::string& name : names) {
      md += " " + std::to_string(confusion[row][name].get<int>()) + " |";
    }
    md += " " + std::to_string(confusion[row]["missed"].get<int>()) + " |\n";
  }
  md += "| (nothing) |";
  for (const std::string& name : names) {
    md += " " + std::to_string(confusion["unpaired"][name].get<int>()) + " |";
  }
  md += " |\n";
  return md;
}

Status RunBenchDetector(const BenchDetectorArgs& args) {
  if (args.threads < 1) return Status::Error("--threads must be at least 1");
  if (!(args.confusion_conf >= 0.0 && args.confusion_conf <= 1.0)) {
    return Status::Error("--confusion-conf must be 0..1");
  }
  detection::YoloOptions options;
  SEMCHAIN_RETURN_IF_ERROR(detection::ParseInputSize(args.input, &options));
  // Scored as ultralytics validates: every box down to a confidence of 0.001, NMS at IoU 0.7.
  options.confidence_threshold = 0.001;
  options.nms_iou_threshold = 0.7;
  Result<detection::YoloDataset> dataset = detection::LoadYoloDataset(args.data);
  if (!dataset.ok()) return dataset.status();
  cv::setNumThreads(args.threads);
  Result<std::unique_ptr<detection::YoloDetector>> detector =
      detection::LoadYoloDetector(args.model, args.classes, options, args.class_map);
  if (!detector.ok()) return detector.status();
  SEMCHAIN_RETURN_IF_ERROR(EnsureWritableDirectory(args.out));
  std::unique_ptr<ProgressBar> bar;  // made once the number of images is known
  Result<detection::DetectorBenchmark> result =
      detection::BenchmarkDetector(**detector, *dataset, args.split,
                                   [&bar](int done, int total) {
                                     if (!bar)
                                       bar = std::make_unique<ProgressBar>("bench detector", total);
                                     bar->Update(static_cast<std::size_t>(done));
                                   },
                                   {.min_score = args.confusion_conf});
  if (!result.ok()) return result.status();
  if (bar) bar->Finish();
  const detection::YoloDetector::Cost cost = (*detector)->ModelCost();
  nlohmann::json json;
  json["model"] = args.model;
  json["data"] = args.data;
  json["split"] = args.split;
  json["input"] = std::to_string((*detector)->options().input_width) + "x" +
                  std::to_string((*detector)->options().input_height);
  json["threads"] = args.threads;
  json["images"] = result->images;
  json["objects"] = result->truths;
  json["map50"] = result->accuracy.map50;
  json["map50_95"] = result->accuracy.map50_95;
  json["precision"] = result->accuracy.precision;
  json["recall"] = result->accuracy.recall;
  json["confidence_at_best_f1"] = result->accuracy.confidence;
  json["ms_per_frame"] = result->mean_ms;
  json["median_ms_per_frame"] = result->median_ms;
  json["gflops"] = cost.gflops;
  json["parameters"] = static_cast<double>(cost.parameters);
  json["file_mb"] = static_cast<double>(fs::file_size(args.model)) / 1e6;
  for (std::size_t c = 0; c < dataset->names.size(); ++c) {
    const detection::ClassAccuracy& accuracy = result->accuracy.classes[c];
    json["classes"][dataset->names[c]] = {
        {"objects", accuracy.truths}, {"ap50", accuracy.ap50}, {"ap50_95", accuracy.ap50_95}};
  }
  json["confusion_conf"] = args.confusion_conf;
  const int n = static_cast<int>(dataset->names.size());
  for (int t = 0; t < n; ++t) {
    nlohmann::json& row = json["confusion"][dataset->names[t]];
    for (int d = 0; d < n; ++d) row[dataset->names[d]] = result->confusion.Count(t, d);
    row["missed"] = result->confusion.Count(t, n);
  }
  for (int d = 0; d < n; ++d) {
    json["confusion"]["unpaired"][dataset->names[d]] = result->confusion.Unpaired(d);
  }
  const fs::path out(args.out);
  SEMCHAIN_RETURN_IF_ERROR(WriteFileAtomically(out / "results.json", json.dump(2) + "\n"));
  SEMCHAIN_RETURN_IF_ERROR(WriteFileAtomically(out / "results.md", Markdown(json, dataset->names)));
  std::printf("mAP@0.5 %.3f  mAP@0.5:0.95 %.3f  P %.3f  R %.3f  %.1f ms/frame  %.2f GFLOPs\n",
              result->accuracy.map50, result->accuracy.map50_95, result->accuracy.precision,
              result->accuracy.recall, result->mean_ms, cost.gflops);
  std::printf("wrote %s\n", (out / "results.md").string().c_str());
  return Status::Ok();
}

}  // namespace

void AddBenchDetector(CLI::App& bench, int& exit_code) {
  CLI::App* command = bench.add_subcommand(
      "detector",
      "Score a YOLOv8-format ONNX detector on a data set split (seed 000 Table 2): mAP@0.5, "
      "mAP@0.5:0.95, precision, recall, AP per class, ms per frame of the C++ runtime, GFLOPs, "
      "parameters and file size, and which classes it mixes up (a confusion table) -> "
      "DIR/results.json and DIR/results.md");
  auto args = std::make_shared<BenchDetectorArgs>();
  command->add_option("--model", args->model, "ONNX model (raw or decoded YOLOv8 head)")
      ->required()
      ->transform(ShippedFile());
  command
      ->add_option("--classes", args->classes,
                   "Class names, one per line (default: the .names file beside the model)")
      ->transform(ShippedFile());
  command->add_option("--class-map", args->class_map,
                      "YAML map 'model class: semchain class' (e.g. config/classes/coco.yaml): a "
                      "model of other classes scored on a data set of semchain's");
  command->add_option("--data", args->data, "The data set's data.yaml")->required();
  command->add_option("--split", args->split, "train, val or test")->capture_default_str();
  command
      ->add_option("--input", args->input,
                   "Network input WIDTHxHEIGHT, or auto: the model's export size")
      ->capture_default_str();
  command->add_option("--threads", args->threads, "OpenCV threads for inference")
      ->capture_default_str();
  command
      ->add_option("--confusion-conf", args->confusion_conf,
                   "Confidence from which detections count in the confusion table (what the "
                   "detector named each labelled object)")
      ->capture_default_str();
  command->add_option("--out", args->out, "Output directory")->required();
  command->callback([args, &exit_code] {
    const Status status = RunBenchDetector(*args);
    exit_code = status.ok() ? 0 : ReportError(status);
  });
}

}  // namespace semchain::app
