// Fuzz target: maps as `semchain plan`, `render`, `semantic` and `localize` read them: map.yaml,
// then the image it names (the input holds both, split at kFileSeparator), then the grid.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "mapping/map_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::string> files = semchain::fuzz::SplitInput(data, size, 2);
  const semchain::fuzz::ScratchFolder folder;
  folder.Write("map.pgm", files[1]);
  const semchain::Result<semchain::mapping::MapImage> map =
      semchain::mapping::ReadMap(folder.Write("map.yaml", files[0]));
  if (map.ok()) (void)semchain::mapping::MapImageToGrid(*map);
  return 0;
}
