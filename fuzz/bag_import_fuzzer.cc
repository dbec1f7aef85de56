// Fuzz target: `semchain bag import FILE.bag --out RUN` (ImportBagToRun): the input is the bag
// file. rosbag itself is Debian's (not instrumented), so the fuzzer mostly explores what reaches
// semchain's side — the bag's structure as the pre-check reads it, the messages' contents — but
// a crash inside rosbag on a malformed bag is still a crash of `semchain bag import`.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "ros/bag_import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const semchain::fuzz::ScratchFolder folder;
  const std::filesystem::path bag = folder.Write("input.bag", semchain::fuzz::Bytes(data, size));
  semchain::ros1::BagImportOptions options;
  options.show_progress = false;
  (void)semchain::ros1::ImportBagToRun(bag, folder.path() / "run", options);
  return 0;
}
