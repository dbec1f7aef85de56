// Milliseconds per frame of the YOLOv8-format detector (letterbox, OpenCV DNN forward pass, DFL
// decoding, class-wise NMS) on a 640 x 480 frame, with OpenCV on 2 threads:
//   - a YOLOv8n-size raw-head model at 640x640, 320x320 and 320x256, and at 640x640 the forward
//     pass and the post-processing apart; random weights are enough
//     for timing: make one with `/usr/bin/python3 tools/make_yolov8n_random.py` (python3-torch)
//     and pass its path as SEMCHAIN_YOLOV8N_ONNX=PATH or --model=PATH; without it these are
//     skipped;
//   - the committed tiny test model (src/detection/testdata), always.
// SEMCHAIN_BENCH_THREADS overrides the thread count.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>

#include "detection/class_nms.h"
#include "detection/letterbox.h"
#include "detection/testing/square_scene.h"
#include "detection/yolo_detector.h"
#include "detection/yolo_head.h"

namespace semchain::detection {
namespace {

void BM_Detect(benchmark::State& state, const std::string& model, cv::Size input) {
  Result<std::vector<std::string>> names = LoadModelClassNames(model, {});
  YoloOptions options;
  options.input_width = input.width;
  options.input_height = input.height;
  Result<std::unique_ptr<YoloDetector>> detector =
      names.ok() ? YoloDetector::Load(model, *names, options)
                 : Result<std::unique_ptr<YoloDetector>>(names.status());
  if (!detector.ok()) {
    state.SkipWithError(detector.status().message().c_str());
    return;
  }
  const cv::Mat frame = testing::SquareImage(testing::SceneSquares());
  std::size_t found = 0;
  for (auto _ : state) {
    Result<std::vector<Detection>> detections = (*detector)->Detect(frame);
    if (!detections.ok()) {
      state.SkipWithError(detections.status().message().c_str());
      return;
    }
    found = detections->size();
  }
  state.counters["detections"] = double(found);
}

// The parts of BM_Detect: OpenCV's forward pass alone (blob and forward), and the decoding and
// NMS of its output alone. Random weights give more candidates than a trained model would.
// The network's output on a grey input, or an error message.
Result<cv::Mat> GreyOutput(cv::dnn::Net& net, cv::Size input) {
  try {
    net.setInput(cv::dnn::blobFromImage(cv::Mat(input, CV_8UC3, cv::Scalar::all(kLetterboxGrey)),
                                        1.0 / 255.0));
    return net.forward().clone();
  } catch (const cv::Exception& error) {
    return Status::Error(error.what());
  }
}

Result<cv::dnn::Net> ReadModel(const std::string& model) {
  try {
    return cv::dnn::readNetFromONNX(model);
  } catch (const cv::Exception& error) {
    return Status::Error(error.what());
  }
}

void BM_Forward(benchmark::State& state, const std::string& model, cv::Size input) {
  Result<cv::dnn::Net> net = ReadModel(model);
  if (!net.ok() || !GreyOutput(*net, input).ok()) {
    state.SkipWithError("OpenCV cannot run the model");
    return;
  }
  const cv::Mat image(input, CV_8UC3, cv::Scalar::all(kLetterboxGrey));
  for (auto _ : state) {
    net->setInput(cv::dnn::blobFromImage(image, 1.0 / 255.0));
    const cv::Mat output = net->forward();
    benchmark::DoNotOptimize(output.data);
  }
}

void BM_Postprocess(benchmark::State& state, const std::string& model, cv::Size input) {
  Result<cv::dnn::Net> net = ReadModel(model);
  Result<cv::Mat> output = net.ok() ? GreyOutput(*net, input) : Result<cv::Mat>(net.status());
  if (!output.ok()) {
    state.SkipWithError("OpenCV cannot run the model");
    return;
  }
  Result<HeadLayout> head = IdentifyHead(*output, output->size[1] - 4 * kRegMax, input);
  if (!head.ok()) {
    state.SkipWithError(head.status().message().c_str());
    return;
  }
  const std::vector<Anchor> anchors = MakeAnchors(input);
  const YoloOptions options;
  std::size_t candidates = 0, kept = 0;
  for (auto _ : state) {
    const std::vector<Candidate> found =
        DecodeHead(*output, *head, anchors, options.confidence_threshold);
    candidates = found.size();
    kept = ClassWiseNms(found, options.nms_iou_threshold, options.max_detections).size();
  }
  state.counters["candidates"] = double(candidates);
  state.counters["kept"] = double(kept);
}

// The YOLOv8n model from --model=PATH (removed from the arguments) or SEMCHAIN_YOLOV8N_ONNX.
std::string YoloV8nPath(int& argc, char** argv) {
  std::string path;
  if (const char* env = std::getenv("SEMCHAIN_YOLOV8N_ONNX")) path = env;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--model=", 0) != 0) continue;
    path = arg.substr(8);
    for (int j = i; j + 1 < argc; ++j) argv[j] = argv[j + 1];
    --argc;
    break;
  }
  return path;
}

}  // namespace
}  // namespace semchain::detection

int main(int argc, char** argv) {
  namespace det = semchain::detection;
  const std::string yolov8n = det::YoloV8nPath(argc, argv);
  const char* threads = std::getenv("SEMCHAIN_BENCH_THREADS");
  cv::setNumThreads(threads ? std::atoi(threads) : 2);
  benchmark::Initialize(&argc, argv);
  const std::string tiny = det::testing::TestModel("tiny_squares_raw.onnx").string();
  benchmark::RegisterBenchmark("BM_TinyRaw/640x640", det::BM_Detect, tiny, cv::Size(640, 640))
      ->Unit(benchmark::kMillisecond);
  std::error_code ec;
  if (!yolov8n.empty() && std::filesystem::is_regular_file(yolov8n, ec)) {
    for (const cv::Size input : {cv::Size(640, 640), cv::Size(320, 320), cv::Size(320, 256)}) {
      const std::string name =
          "BM_YoloV8nRaw/" + std::to_string(input.width) + "x" + std::to_string(input.height);
      benchmark::RegisterBenchmark(name.c_str(), det::BM_Detect, yolov8n, input)
          ->Unit(benchmark::kMillisecond)
          ->MinTime(2.0);
    }
    const cv::Size full(640, 640);
    benchmark::RegisterBenchmark("BM_YoloV8nForward/640x640", det::BM_Forward, yolov8n, full)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(2.0);
    benchmark::RegisterBenchmark("BM_YoloV8nPostprocess/640x640", det::BM_Postprocess, yolov8n,
                                 full)
        ->Unit(benchmark::kMillisecond);
  } else {
    std::fprintf(stderr,
                 "detect_bench: no YOLOv8n model (SEMCHAIN_YOLOV8N_ONNX or --model=PATH; make "
                 "one with tools/make_yolov8n_random.py): timing the tiny test model only\n");
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
