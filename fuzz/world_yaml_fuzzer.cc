// Fuzz target: world files as `semchain simulate` reads them: ParseWorld, then ValidateWorld.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "sim/world.h"
#include "sim/world_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(semchain::fuzz::Bytes(data, size));
  const semchain::Result<semchain::sim::World> world =
      semchain::sim::ParseWorld(text, "world.yaml");
  if (world.ok()) (void)semchain::sim::ValidateWorld(*world, "world.yaml");
  return 0;
}
