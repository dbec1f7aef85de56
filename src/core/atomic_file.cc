#include "core/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>

namespace semchain {
namespace {

std::filesystem::path TemporarySibling(const std::filesystem::path& path) {
  // The pid keeps two processes writing the same file from sharing a temporary.
  std::filesystem::path temp = path;
  temp += ".tmp." + std::to_string(::getpid());
  return temp;
}

Status ErrnoError(const std::filesystem::path& path, const char* what) {
  return Status::Error(path.string() + ": " + what + ": " + std::strerror(errno));
}

}  // namespace

Status WriteFileAtomically(const std::filesystem::path& path,
                           const std::function<Status(std::ostream&)>& write) {
  const std::filesystem::path temp = TemporarySibling(path);
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) return ErrnoError(path, "cannot create file");
    const Status status = write(out);
    out.flush();
    if (!status.ok() || !out) {
      out.close();
      std::error_code ignored;
      std::filesystem::remove(temp, ignored);
      return status.ok() ? ErrnoError(path, "write failed") : status;
    }
  }
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    const Status error = ErrnoError(path, "cannot rename temporary file");
    std::error_code ignored;
    std::filesystem::remove(temp, ignored);
    return error;
  }
  return Status::Ok();
}

Status WriteFileAtomically(const std::filesystem::path& path, std::string_view contents) {
  return WriteFileAtomically(path, [contents](std::ostream& out) {
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    return Status::Ok();
  });
}

Status EnsureWritableDirectory(const std::filesystem::path& directory) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) {
    return Status::Error(directory.string() + ": cannot create directory: " + error.message());
  }
  if (!std::filesystem::is_directory(directory)) {
    return Status::Error(directory.string() + ": not a directory");
  }
  if (::access(directory.c_str(), W_OK) != 0) {
    return ErrnoError(directory, "directory not writable");
  }
  return Status::Ok();
}

Result<std::string> ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return ErrnoError(path, "cannot open file");
  std::ostringstream contents;
  contents << in.rdbuf();
  if (in.bad()) return ErrnoError(path, "read failed");
  return contents.str();
}

}  // namespace semchain
