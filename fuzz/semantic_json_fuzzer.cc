// Fuzz target: semantic.json as `semchain render` and `localize` read it (ReadSemanticJson).
#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "semantic/semantic_map_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const semchain::fuzz::ScratchFolder folder;
  (void)semchain::semantic::ReadSemanticJson(
      folder.Write("semantic.json", semchain::fuzz::Bytes(data, size)));
  return 0;
}
