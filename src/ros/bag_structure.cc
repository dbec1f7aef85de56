#include "ros/bag_structure.h"

#include <bzlib.h>
#include <roslz4/lz4s.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace semchain::ros1 {
namespace {

constexpr std::string_view kMagic = "#ROSBAG V2.0\n";

// Record ops of the 2.0 format (rosbag/constants.h).
enum Op : std::uint8_t {
  kMessageData = 0x02,
  kBagHeader = 0x03,
  kIndexData = 0x04,
  kChunk = 0x05,
  kChunkInfo = 0x06,
  kConnection = 0x07,
};

std::uint32_t ReadU32(const char* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);  // the format is little-endian, as every machine ROS 1 runs on
  return v;
}
std::uint64_t ReadU64(const char* p) {
  std::uint64_t v;
  std::memcpy(&v, p, 8);
  return v;
}

// A record's header fields, name → value bytes.
using Fields = std::map<std::string, std::string>;

// Splits a header (or a connection record's data, which has the same layout) into fields.
Result<Fields> ParseFields(std::string_view bytes) {
  Fields fields;
  std::size_t at = 0;
  while (at < bytes.size()) {
    if (bytes.size() - at < 4) return Status::Error("a header field's length is cut off");
    const std::uint32_t length = ReadU32(bytes.data() + at);
    at += 4;
    if (length > bytes.size() - at) {
      return Status::Error("a header field of " + std::to_string(length) + " bytes, " +
                           std::to_string(bytes.size() - at) + " left in the header");
    }
    const std::string_view field = bytes.substr(at, length);
    at += length;
    const std::size_t equals = field.find('=');
    if (equals == std::string_view::npos) return Status::Error("a header field without '='");
    fields[std::string(field.substr(0, equals))] = std::string(field.substr(equals + 1));
  }
  return fields;
}

// A field rosbag reads as a number of exactly 'size' bytes.
Result<std::uint64_t> NumberField(const Fields& fields, const std::string& name, std::size_t size) {
  const auto it = fields.find(name);
  if (it == fields.end()) return Status::Error("no '" + name + "' field");
  if (it->second.size() != size) {
    return Status::Error("field '" + name + "' has " + std::to_string(it->second.size()) +
                         " bytes, not " + std::to_string(size));
  }
  return size == 1   ? static_cast<std::uint8_t>(it->second[0])
         : size == 4 ? ReadU32(it->second.data())
                     : ReadU64(it->second.data());
}

// One record: its header fields and where its data lies.
struct Record {
  std::uint64_t offset = 0;  // of the record (its header length)
  Fields fields;
  std::uint8_t op = 0;
  std::uint64_t data_offset = 0;
  std::uint32_t data_length = 0;
  std::uint64_t end = 0;  // the next record's offset
};

// Reads the record at 'offset' from 'read(offset, count, out)' that holds 'size' bytes in all.
template <typename ReadBytes>
Result<Record> ReadRecord(const ReadBytes& read, std::uint64_t offset, std::uint64_t size,
                          const BagStructureLimits& limits) {
  Record record;
  record.offset = offset;
  char length_bytes[4];
  if (size - offset < 4) return Status::Error("a record's header length is cut off");
  SEMCHAIN_RETURN_IF_ERROR(read(offset, 4, length_bytes));
  const std::uint32_t header_length = ReadU32(length_bytes);
  if (header_length > limits.max_header_bytes) {
    return Status::Error("a record header of " + std::to_string(header_length) +
                         " bytes (at most " + std::to_string(limits.max_header_bytes) + ")");
  }
  if (header_length > size - offset - 4) {
    return Status::Error("a record header of " + std::to_string(header_length) + " bytes, " +
                         std::to_string(size - offset - 4) + " left");
  }
  std::string header(header_length, '\0');
  SEMCHAIN_RETURN_IF_ERROR(read(offset + 4, header_length, header.data()));
  Result<Fields> fields = ParseFields(header);
  if (!fields.ok()) return fields.status();
  record.fields = std::move(*fields);
  const Result<std::uint64_t> op = NumberField(record.fields, "op", 1);
  if (!op.ok()) return op.status();
  record.op = static_cast<std::uint8_t>(*op);
  const std::uint64_t data_length_at = offset + 4 + header_length;
  if (size - data_length_at < 4) return Status::Error("a record's data length is cut off");
  SEMCHAIN_RETURN_IF_ERROR(read(data_length_at, 4, length_bytes));
  record.data_length = ReadU32(length_bytes);
  record.data_offset = data_length_at + 4;
  if (record.data_length > size - record.data_offset) {
    return Status::Error("record data of " + std::to_string(record.data_length) + " bytes, " +
                         std::to_string(size - record.data_offset) + " left");
  }
  record.end = record.data_offset + record.data_length;
  return record;
}

// What a chunk's records say (uncompressed): where its messages start, which connections its
// records name.
struct ChunkContents {
  std::set<std::uint32_t> message_starts;
  std::set<std::uint32_t> connections;
};

// The records inside one chunk: message data and connections only, each whole.
Result<ChunkContents> CheckChunkRecords(const std::string& data, const BagStructureLimits& limits) {
  const auto read = [&data](std::uint64_t at, std::uint64_t count, char* out) {
    std::memcpy(out, data.data() + at, count);
    return Status::Ok();
  };
  ChunkContents contents;
  for (std::uint64_t at = 0; at < data.size();) {
    const std::string where = "inside the chunk at byte " + std::to_string(at);
    Result<Record> record = ReadRecord(read, at, data.size(), limits);
    if (!record.ok()) return record.status().WithContext(where);
    if (record->op != kMessageData && record->op != kConnection) {
      return Status::Error(where + ": a record of op " + std::to_string(record->op) +
                           " (a chunk holds messages and connections)");
    }
    const Result<std::uint64_t> connection = NumberField(record->fields, "conn", 4);
    if (!connection.ok()) return connection.status().WithContext(where);
    contents.connections.insert(static_cast<std::uint32_t>(*connection));
    if (record->op == kConnection) {
      const Result<Fields> header =
          ParseFields(std::string_view(data).substr(record->data_offset, record->data_length));
      if (!header.ok()) return header.status().WithContext(where + ": connection");
    } else {
      const Result<std::uint64_t> time = NumberField(record->fields, "time", 8);
      if (!time.ok()) return time.status().WithContext(where + ": message");
      contents.message_starts.insert(static_cast<std::uint32_t>(at));
    }
    at = record->end;
  }
  return contents;
}

// The chunk's data decompressed to exactly its declared size.
Result<std::string> Decompress(const std::string& compression, std::string data,
                               std::uint32_t size) {
  if (compression == "none") {
    if (data.size() != size) {
      return Status::Error("an uncompressed chunk of " + std::to_string(data.size()) +
                           " bytes that says it holds " + std::to_string(size));
    }
    return data;
  }
  std::string out(size, '\0');
  unsigned int produced = size;
  int result = 0;
  if (compression == "bz2") {
    result = BZ2_bzBuffToBuffDecompress(out.data(), &produced, data.data(),
                                        static_cast<unsigned int>(data.size()), 0, 0);
    if (result != BZ_OK) return Status::Error("bz2 data that does not decompress");
  } else if (compression == "lz4") {
    result = roslz4_buffToBuffDecompress(data.data(), static_cast<unsigned int>(data.size()),
                                         out.data(), &produced);
    if (result != ROSLZ4_OK) return Status::Error("lz4 data that does not decompress");
  } else {
    return Status::Error("a chunk compressed with '" + compression + "' (none, bz2 or lz4)");
  }
  if (produced != size) {
    return Status::Error("a chunk that decompresses to " + std::to_string(produced) +
                         " bytes but says " + std::to_string(size));
  }
  return out;
}

// Bytes of the bag file by offset, for ReadRecord.
struct FileReader {
  std::ifstream* in;
  Status operator()(std::uint64_t at, std::uint64_t count, char* out) const {
    in->clear();
    in->seekg(static_cast<std::streamoff>(at));
    in->read(out, static_cast<std::streamsize>(count));
    if (!*in) return Status::Error("cannot read " + std::to_string(count) + " bytes");
    return Status::Ok();
  }
};

class BagChecker {
 public:
  BagChecker(std::ifstream& in, std::uint64_t size, const BagStructureLimits& limits)
      : in_(in), size_(size), limits_(limits) {}

  Status Run() {
    for (std::uint64_t at = kMagic.size(); at < size_;) {
      Result<Record> record = ReadRecord(Reader(), at, size_, limits_);
      if (!record.ok()) return At(at, record.status().message());
      SEMCHAIN_RETURN_IF_ERROR(CheckRecord(*record));
      records_[at] = record->op;
      at = record->end;
    }
    return CheckIndex();
  }

 private:
  FileReader Reader() const { return FileReader{&in_}; }

  // The record's data bytes (bounded by the file: ReadRecord checked the length).
  Result<std::string> ReadData(const Record& record) const {
    std::string data(record.data_length, '\0');
    SEMCHAIN_RETURN_IF_ERROR(Reader()(record.data_offset, record.data_length, data.data()));
    return data;
  }

  Status At(std::uint64_t offset, const std::string& what) const {
    return Status::Error("byte " + std::to_string(offset) + ": " + what);
  }

  Status CheckRecord(const Record& record) {
    const auto number = [&](const std::string& name, std::size_t size) {
      return NumberField(record.fields, name, size);
    };
    switch (record.op) {
      case kBagHeader: {
        if (record.offset != kMagic.size()) return At(record.offset, "a second bag header");
        const Result<std::uint64_t> index_pos = number("index_pos", 8);
        const Result<std::uint64_t> connections = number("conn_count", 4);
        const Result<std::uint64_t> chunks = number("chunk_count", 4);
        for (const Status& s : {index_pos.status(), connections.status(), chunks.status()}) {
          if (!s.ok()) return At(record.offset, "bag header: " + s.message());
        }
        header_ = Header{*index_pos, *connections, *chunks};
        return Status::Ok();
      }
      case kChunk: {
        const Result<std::uint64_t> size = number("size", 4);
        if (!size.ok()) return At(record.offset, "chunk: " + size.status().message());
        const auto compression = record.fields.find("compression");
        if (compression == record.fields.end()) return At(record.offset, "chunk: no compression");
        if (*size > limits_.max_chunk_bytes || record.data_length > limits_.max_chunk_bytes) {
          return At(record.offset,
                    "a chunk of " +
                        std::to_string(std::max<std::uint64_t>(*size, record.data_length)) +
                        " bytes (at most " + std::to_string(limits_.max_chunk_bytes) + ")");
        }
        Result<std::string> data = ReadData(record);
        if (!data.ok()) return data.status();
        Result<std::string> plain =
            Decompress(compression->second, std::move(*data), static_cast<std::uint32_t>(*size));
        if (!plain.ok()) return At(record.offset, plain.status().message());
        Result<ChunkContents> contents = CheckChunkRecords(*plain, limits_);
        if (!contents.ok()) return At(record.offset, contents.status().message());
        for (const std::uint32_t connection : contents->connections) {
          referenced_.emplace(connection, record.offset);
        }
        chunk_ = std::move(*contents);
        return Status::Ok();
      }
      case kIndexData: {
        // rosbag reads each chunk's index records right after it and follows their offsets
        // into the chunk's records.
        const Result<std::uint64_t> version = number("ver", 4);
        const Result<std::uint64_t> count = number("count", 4);
        const Result<std::uint64_t> connection = number("conn", 4);
        for (const Status& s : {version.status(), count.status(), connection.status()}) {
          if (!s.ok()) return At(record.offset, "index: " + s.message());
        }
        referenced_.emplace(static_cast<std::uint32_t>(*connection), record.offset);
        if (*version != 1) return At(record.offset, "index version " + std::to_string(*version));
        if (*count * 12 != record.data_length) {
          return At(record.offset, "an index of " + std::to_string(*count) + " entries in " +
                                       std::to_string(record.data_length) + " bytes");
        }
        if (!chunk_) return At(record.offset, "an index before any chunk");
        const Result<std::string> entries = ReadData(record);
        if (!entries.ok()) return entries.status();
        for (std::uint64_t i = 0; i < *count; ++i) {
          const std::uint32_t offset = ReadU32(entries->data() + i * 12 + 8);
          if (chunk_->message_starts.count(offset) == 0) {
            return At(record.offset, "index entry " + std::to_string(i) + " points at byte " +
                                         std::to_string(offset) +
                                         " of its chunk, where no message starts");
          }
        }
        return Status::Ok();
      }
      case kChunkInfo: {
        const Result<std::uint64_t> version = number("ver", 4);
        const Result<std::uint64_t> position = number("chunk_pos", 8);
        const Result<std::uint64_t> count = number("count", 4);
        for (const Status& s : {version.status(), position.status(), count.status(),
                                number("start_time", 8).status(), number("end_time", 8).status()}) {
          if (!s.ok()) return At(record.offset, "chunk info: " + s.message());
        }
        if (*version != 1) {
          return At(record.offset, "chunk info version " + std::to_string(*version));
        }
        if (*count * 8 != record.data_length) {
          return At(record.offset, "chunk info of " + std::to_string(*count) + " connections in " +
                                       std::to_string(record.data_length) + " bytes");
        }
        chunk_positions_.emplace_back(record.offset, *position);
        const Result<std::string> entries = ReadData(record);
        if (!entries.ok()) return entries.status();
        for (std::uint64_t i = 0; i < *count; ++i) {
          referenced_.emplace(ReadU32(entries->data() + i * 8), record.offset);
        }
        return Status::Ok();
      }
      case kConnection: {
        const Result<std::uint64_t> connection = number("conn", 4);
        if (!connection.ok())
          return At(record.offset, "connection: " + connection.status().message());
        if (record.fields.count("topic") == 0) return At(record.offset, "connection: no topic");
        known_.insert(static_cast<std::uint32_t>(*connection));
        const Result<std::string> data = ReadData(record);
        if (!data.ok()) return data.status();
        const Result<Fields> header = ParseFields(*data);
        if (!header.ok()) return At(record.offset, "connection: " + header.status().message());
        return Status::Ok();
      }
      case kMessageData:
        return At(record.offset, "a message outside any chunk");
      default:
        return At(record.offset, "a record of unknown op " + std::to_string(record.op));
    }
  }

  // The index section rosbag reads on open: conn_count connections, then chunk_count chunk
  // infos from index_pos on, each chunk info naming a chunk record.
  Status CheckIndex() const {
    if (!header_) return Status::Error("no bag header (the file ends after its first line)");
    if (header_->index_pos == 0) {
      return Status::Error("the bag was not closed (no index; `rosbag reindex` it)");
    }
    auto it = records_.find(header_->index_pos);
    if (it == records_.end()) {
      return Status::Error("the bag header's index position " + std::to_string(header_->index_pos) +
                           " is not a record");
    }
    for (std::uint64_t i = 0; i < header_->connections; ++i, ++it) {
      if (it == records_.end() || it->second != kConnection) {
        return Status::Error("the index names " + std::to_string(header_->connections) +
                             " connections; record " + std::to_string(i) + " is not one");
      }
    }
    for (std::uint64_t i = 0; i < header_->chunks; ++i, ++it) {
      if (it == records_.end() || it->second != kChunkInfo) {
        return Status::Error("the index names " + std::to_string(header_->chunks) +
                             " chunks; chunk info " + std::to_string(i) + " is missing");
      }
    }
    // rosbag looks every connection a chunk, index or chunk info names up among those of the
    // index section (and dereferences what it finds).
    for (const auto& [connection, where] : referenced_) {
      if (known_.count(connection) == 0) {
        return At(where, "connection " + std::to_string(connection) +
                             " is not among the bag's connections");
      }
    }
    for (const auto& [info, position] : chunk_positions_) {
      const auto chunk = records_.find(position);
      if (chunk == records_.end() || chunk->second != kChunk) {
        return At(info, "chunk info points at byte " + std::to_string(position) +
                            ", where no chunk starts");
      }
    }
    return Status::Ok();
  }

  struct Header {
    std::uint64_t index_pos = 0, connections = 0, chunks = 0;
  };

  std::ifstream& in_;
  std::uint64_t size_;
  BagStructureLimits limits_;
  std::optional<Header> header_;
  std::optional<ChunkContents> chunk_;             // the last chunk seen
  std::map<std::uint64_t, std::uint8_t> records_;  // offset → op, top level
  std::vector<std::pair<std::uint64_t, std::uint64_t>> chunk_positions_;  // info → chunk
  std::set<std::uint32_t> known_;                                         // the index's connections
  std::map<std::uint32_t, std::uint64_t> referenced_;  // connection → first record naming it
};

}  // namespace

Status CheckBagStructure(const std::filesystem::path& path, const BagStructureLimits& limits) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) return Status::Error(path.string() + ": " + error.message());
  std::ifstream in(path, std::ios::binary);
  if (!in) return Status::Error(path.string() + ": cannot open");
  std::string magic(kMagic.size(), '\0');
  if (size < kMagic.size() || !in.read(magic.data(), static_cast<std::streamsize>(magic.size())) ||
      magic != kMagic) {
    return Status::Error(path.string() +
                         ": not a readable ROS bag: its first line is not '#ROSBAG V2.0'");
  }
  BagChecker checker(in, size, limits);
  return checker.Run().WithContext(path.string());
}

}  // namespace semchain::ros1
