// Fuzz target: `--model M.onnx --classes NAMES` (LoadYoloDetector, then the model's cost as
// `bench detector` counts it): the input holds the names file and the model, split at
// kFileSeparator.
#include <cstddef>
#include <cstdint>

#include "detection/yolo_detector.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::string> files = semchain::fuzz::SplitInput(data, size, 2);
  const semchain::fuzz::ScratchFolder folder;
  const std::filesystem::path names = folder.Write("model.names", files[0]);
  semchain::detection::YoloOptions options;
  options.input_width = 64;  // small, so that a model that loads runs fast
  options.input_height = 64;
  auto detector =
      semchain::detection::LoadYoloDetector(folder.Write("model.onnx", files[1]), names, options);
  // What `bench detector` asks of a model that loads (OpenCV's own FLOPs count crashed on one).
  if (detector.ok()) (void)(*detector)->ModelCost();
  return 0;
}
