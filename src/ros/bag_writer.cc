#include "ros/bag_writer.h"

#include <unistd.h>

#include <system_error>

#include "core/atomic_file.h"

namespace semchain::ros1 {
namespace fs = std::filesystem;

BagWriter::BagWriter(fs::path path, fs::path temporary)
    : path_(std::move(path)), temporary_(std::move(temporary)) {}

Result<std::unique_ptr<BagWriter>> BagWriter::Create(const fs::path& path,
                                                     BagCompression compression) {
  std::error_code ignored;
  if (fs::is_directory(path, ignored)) return Status::Error(path.string() + ": is a directory");
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  SEMCHAIN_RETURN_IF_ERROR(EnsureWritableDirectory(parent));
  fs::path temporary = path;
  temporary += ".tmp." + std::to_string(::getpid());
  std::unique_ptr<BagWriter> writer(new BagWriter(path, temporary));
  try {
    writer->bag_.open(temporary.string(), rosbag::bagmode::Write);
    switch (compression) {
      case BagCompression::kNone:
        writer->bag_.setCompression(rosbag::compression::Uncompressed);
        break;
      case BagCompression::kLz4:
        writer->bag_.setCompression(rosbag::compression::LZ4);
        break;
      case BagCompression::kBz2:
        writer->bag_.setCompression(rosbag::compression::BZ2);
        break;
    }
  } catch (const std::exception& error) {
    return Status::Error(path.string() + ": cannot create bag: " + error.what());
  }
  return writer;
}

BagWriter::~BagWriter() {
  if (finished_) return;
  try {
    bag_.close();
  } catch (const std::exception&) {
    // The file is removed below whatever state it is in.
  }
  std::error_code ignored;
  fs::remove(temporary_, ignored);
}

Status BagWriter::Finish() {
  try {
    bag_.close();
  } catch (const std::exception& error) {
    return Status::Error(temporary_.string() + ": cannot close bag: " + error.what());
  }
  std::error_code error;
  fs::rename(temporary_, path_, error);
  if (error)
    return Status::Error(path_.string() + ": cannot move bag into place: " + error.message());
  finished_ = true;
  return Status::Ok();
}

}  // namespace semchain::ros1
