// Fuzz target: SLAM option files (`semchain slam --config`, config/slam*.yaml).
#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "mapping/slam_options.h"
#include "mapping/slam_options_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const semchain::fuzz::ScratchFolder folder;
  semchain::mapping::SlamOptions options;
  (void)semchain::mapping::LoadSlamOptions(
      folder.Write("slam.yaml", semchain::fuzz::Bytes(data, size)), &options);
  return 0;
}
