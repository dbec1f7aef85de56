// Fuzz target: detections.jsonl as `semchain semantic` and `localize` read it.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "io/detections_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const semchain::fuzz::ScratchFolder folder;
  (void)semchain::ReadDetectionsJsonl(
      folder.Write("detections.jsonl", semchain::fuzz::Bytes(data, size)));
  return 0;
}
