#include "fuzz_input.h"

#include <unistd.h>

#include <fstream>
#include <system_error>

namespace semchain::fuzz {

std::vector<std::string> SplitInput(const std::uint8_t* data, std::size_t size, std::size_t count) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (parts.size() + 1 < count) {
    const std::size_t end = text.find(kFileSeparator, start);
    if (end == std::string_view::npos) break;
    parts.emplace_back(text.substr(start, end - start));
    start = end + kFileSeparator.size();
  }
  parts.emplace_back(text.substr(std::min(start, text.size())));
  parts.resize(count);
  return parts;
}

ScratchFolder::ScratchFolder()
    : path_(std::filesystem::temp_directory_path() /
            ("semchain-fuzz-" + std::to_string(::getpid()))) {
  std::filesystem::create_directories(path_);
}

ScratchFolder::~ScratchFolder() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

std::filesystem::path ScratchFolder::Write(const std::string& name, std::string_view bytes) const {
  const std::filesystem::path file = path_ / name;
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return file;
}

}  // namespace semchain::fuzz
