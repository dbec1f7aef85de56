// Fuzz target: route files of `semchain simulate --route` (LoadWaypoints): the first byte picks
// YAML (odd) or plain text (even), the rest is the file.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "sim/world_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const semchain::fuzz::ScratchFolder folder;
  const char* name = data[0] % 2 == 1 ? "route.yaml" : "route.txt";
  (void)semchain::sim::LoadWaypoints(folder.Write(name, semchain::fuzz::Bytes(data + 1, size - 1)));
  return 0;
}
