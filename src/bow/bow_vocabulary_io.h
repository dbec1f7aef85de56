#pragma once

#include <filesystem>
#include <string>

#include "bow/bow_vocabulary.h"
#include "core/status.h"

// The vocabulary file written by `semchain vocab train` (binary, little-endian):
//   "SCBOWVOC"                       8-byte magic
//   u32 version (1), u32 k, u32 L, u32 descriptor bytes (32), u32 training images N,
//   u32 node count n
//   n × {i32 parent, i32 word, f64 weight, descriptor bytes}   node 0 the root, parents first
//   u64 FNV-1a hash of every byte before it
// Reading checks all of it, so a truncated, corrupt or foreign file is an error naming the
// file, never a crash.
namespace semchain::bow {

inline constexpr std::uint32_t kVocabularyFileVersion = 1;

std::string SerializeVocabulary(const Vocabulary& vocabulary);
Status WriteVocabulary(const std::filesystem::path& path, const Vocabulary& vocabulary);

// Errors read "PATH: <what is wrong>", e.g. "v.bin: truncated (1234 of 5678 bytes)".
Result<Vocabulary> ParseVocabulary(const std::string& bytes, const std::string& source);
Result<Vocabulary> ReadVocabulary(const std::filesystem::path& path);

}  // namespace semchain::bow
