// Fuzz target: keep-out zone files of `semchain plan --keepout` (ReadKeepoutZones).
#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "planning/keepout.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const semchain::fuzz::ScratchFolder folder;
  (void)semchain::planning::ReadKeepoutZones(
      folder.Write("keepout.yaml", semchain::fuzz::Bytes(data, size)));
  return 0;
}
