// Fuzz target: a run's camera.yaml (ReadCameraYaml).
#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "io/camera_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const semchain::fuzz::ScratchFolder folder;
  (void)semchain::ReadCameraYaml(folder.Write("camera.yaml", semchain::fuzz::Bytes(data, size)));
  return 0;
}
