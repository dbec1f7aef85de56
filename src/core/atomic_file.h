#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>

#include "core/status.h"

namespace semchain {

// Writes 'contents' to 'path' so that readers see either the old file or the whole new one:
// the bytes go to a temporary file in the same directory, are flushed, then renamed over
// 'path'. On failure 'path' is untouched and the temporary file removed.
Status WriteFileAtomically(const std::filesystem::path& path, std::string_view contents);

// The same, with the contents produced by 'write' into a stream. A 'write' that returns an
// error Status (or leaves the stream failed) aborts the write without touching 'path'.
Status WriteFileAtomically(const std::filesystem::path& path,
                           const std::function<Status(std::ostream&)>& write);

// Creates 'directory' (and parents) if needed and checks that files can be created in it.
Status EnsureWritableDirectory(const std::filesystem::path& directory);

// Reads a whole file; the error names the file.
Result<std::string> ReadFile(const std::filesystem::path& path);

}  // namespace semchain
