// Fuzz target: CARMEN logs as `semchain slam`, `localize` and `render` read them (ReadLog reads
// the file, then hands its text to ParseLog).
#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "io/carmen.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)semchain::carmen::ParseLog(semchain::fuzz::Bytes(data, size), "log.clf");
  return 0;
}
