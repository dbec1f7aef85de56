// Fuzz target: the vocabulary binary of `semchain vocab` and `localize --vocab`.
#include <cstddef>
#include <cstdint>

#include "bow/bow_vocabulary_io.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)semchain::bow::ParseVocabulary(std::string(semchain::fuzz::Bytes(data, size)), "vocab.bin");
  return 0;
}
