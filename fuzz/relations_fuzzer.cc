// Fuzz target: relation files of `semchain eval` and `bench` (eval::ReadRelations).
#include <cstddef>
#include <cstdint>

#include "eval/relations.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const semchain::fuzz::ScratchFolder folder;
  (void)semchain::eval::ReadRelations(
      folder.Write("relations.txt", semchain::fuzz::Bytes(data, size)));
  return 0;
}
