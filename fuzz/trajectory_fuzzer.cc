// Fuzz target: trajectories (truth.txt, trajectory.txt, `semchain eval` poses) (ReadTrajectory).
#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "io/trajectory_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const semchain::fuzz::ScratchFolder folder;
  (void)semchain::ReadTrajectory(folder.Write("trajectory.txt", semchain::fuzz::Bytes(data, size)));
  return 0;
}
