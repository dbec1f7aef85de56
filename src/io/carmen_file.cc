// Reading and writing whole CARMEN logs, plain or gzip-compressed.
#include <zlib.h>

#include <cerrno>
#include <cstring>
#include <limits>
#include <memory>
#include <string_view>

#include "core/atomic_file.h"
#include "io/carmen.h"

namespace semchain::carmen {
namespace {

bool HasGzipExtension(const std::filesystem::path& path) { return path.extension() == ".gz"; }

// Reads a whole file, decompressing it when it is gzip data (zlib reads plain files as they are).
Result<std::string> ReadMaybeCompressed(const std::filesystem::path& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    return Status::Error(path.string() + ": is a directory, not a log file");
  }
  errno = 0;
  const std::unique_ptr<gzFile_s, int (*)(gzFile)> file(gzopen(path.c_str(), "rb"), gzclose);
  if (file == nullptr) {
    return Status::Error(path.string() +
                         ": cannot open: " + (errno != 0 ? std::strerror(errno) : "out of memory"));
  }
  std::string contents;
  char buffer[1 << 16];
  int n = 0;
  while ((n = gzread(file.get(), buffer, sizeof(buffer))) > 0) {
    contents.append(buffer, static_cast<std::size_t>(n));
  }
  // A truncated gzip file ends with n == 0 and the error set (zlib.h, gzread).
  int code = Z_OK;
  const char* message = gzerror(file.get(), &code);
  if (n < 0 || code != Z_OK) {
    return Status::Error(path.string() +
                         ": read error: " + (code == Z_ERRNO ? std::strerror(errno) : message));
  }
  return contents;
}

// Compresses 'data' into the gzip format (RFC 1952: zlib's deflate with windowBits 15 + 16).
Result<std::string> GzipCompress(std::string_view data) {
  if (data.size() > std::numeric_limits<uInt>::max()) return Status::Error("gzip: too large");
  z_stream stream{};
  if (deflateInit2(&stream, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) !=
      Z_OK) {
    return Status::Error("gzip: cannot initialise the compressor");
  }
  std::string out(deflateBound(&stream, static_cast<uLong>(data.size())), '\0');
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  stream.avail_in = static_cast<uInt>(data.size());
  stream.next_out = reinterpret_cast<Bytef*>(out.data());
  stream.avail_out = static_cast<uInt>(out.size());
  const int result = deflate(&stream, Z_FINISH);
  out.resize(stream.total_out);
  deflateEnd(&stream);
  if (result != Z_STREAM_END) return Status::Error("gzip: compression failed");
  return out;
}

template <typename T>
std::vector<const T*> RecordsOf(const std::vector<Record>& records) {
  std::vector<const T*> selected;
  for (const Record& record : records) {
    if (const T* r = std::get_if<T>(&record)) selected.push_back(r);
  }
  return selected;
}

}  // namespace

std::vector<const Laser*> Log::Lasers() const { return RecordsOf<Laser>(records); }
std::vector<const Odometry*> Log::Odometries() const { return RecordsOf<Odometry>(records); }
std::vector<const TruePose*> Log::TruePoses() const { return RecordsOf<TruePose>(records); }

Result<Log> ReadLog(const std::filesystem::path& path, const ReadOptions& options) {
  Result<std::string> contents = ReadMaybeCompressed(path);
  if (!contents.ok()) return contents.status();
  return ParseLog(*contents, path.string(), options);
}

Result<Log> ParseLog(std::string_view text, const std::string& source, const ReadOptions& options) {
  ReadOptions current = options;  // PARAM lines update it for the lines that follow
  Log log;
  std::size_t line_number = 0;
  for (std::size_t begin = 0; begin < text.size();) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string_view::npos) end = text.size();
    std::string line(text.substr(begin, end - begin));
    begin = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    const std::string where = source + ":" + std::to_string(line_number);
    Result<Record> record = ParseLine(line, where, current);
    if (!record.ok()) return record.status();
    if (const Param* param = std::get_if<Param>(&*record)) {
      SEMCHAIN_RETURN_IF_ERROR(ApplyParam(*param, where, &current));
    }
    log.records.push_back(std::move(*record));
  }
  return log;
}

Status WriteLog(const std::filesystem::path& path, const Log& log) {
  std::string text;
  for (const Record& record : log.records) {
    text += FormatRecord(record);
    text += '\n';
  }
  if (!HasGzipExtension(path)) return WriteFileAtomically(path, text);
  Result<std::string> compressed = GzipCompress(text);
  if (!compressed.ok()) return compressed.status().WithContext(path.string());
  return WriteFileAtomically(path, *compressed);
}

}  // namespace semchain::carmen
