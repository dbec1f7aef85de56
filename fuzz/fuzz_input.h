#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

// Helpers for the fuzz targets (fuzz/README.md): most parsers take a path, so a target writes
// the fuzzer's bytes to files in a scratch folder of its own and hands the parser their paths.
namespace semchain::fuzz {

// The line that separates the files of a multi-file input (a map's YAML and its image, a model
// and its names). It starts with '#', so YAML and text parsers read it as a comment.
inline constexpr std::string_view kFileSeparator = "\n#semchain-fuzz-next-file\n";

// The fuzzer's bytes as text.
inline std::string_view Bytes(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// Splits 'data' at kFileSeparator into exactly 'count' parts (missing ones are empty, the last
// part keeps any further separators).
std::vector<std::string> SplitInput(const std::uint8_t* data, std::size_t size, std::size_t count);

// A folder for one input's files, unique to the process, removed with everything in it when
// the object goes out of scope (so that a long campaign does not fill /tmp).
class ScratchFolder {
 public:
  ScratchFolder();
  ~ScratchFolder();
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;

  // Writes 'bytes' to 'name' in the folder and returns its path.
  std::filesystem::path Write(const std::string& name, std::string_view bytes) const;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace semchain::fuzz
