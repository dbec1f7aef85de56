// Fuzz target: keyframes.json as `semchain localize` and `vocab` read it (ReadKeyframes).
#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "semantic/keyframes.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const semchain::fuzz::ScratchFolder folder;
  (void)semchain::semantic::ReadKeyframes(
      folder.Write("keyframes.json", semchain::fuzz::Bytes(data, size)));
  return 0;
}
