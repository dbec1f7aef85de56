#pragma once

#include <cstdint>
#include <filesystem>

#include "core/status.h"

// A check of a ROS bag's record structure (format 2.0) before rosbag reads it. rosbag trusts the
// lengths and offsets it reads: a header length of 2 GB is allocated before it is compared with
// the file, a chunk's "size" is allocated for decompression, and records inside a chunk are read
// from a buffer at offsets nobody compares with its end. One flipped byte in a recorded bag would
// then stop `semchain bag import` (or the machine) instead of giving an error. The check walks
// every record, decompresses every chunk (bz2, lz4) and verifies that every length, count and
// offset rosbag will follow lands inside the file, inside its chunk and on a record of the kind
// rosbag expects there.
namespace semchain::ros1 {

// Limits on what a bag may ask for (a real recorder's records are far below them).
struct BagStructureLimits {
  std::uint32_t max_header_bytes = 1u << 20;   // one record header (rosbag's are < 1 KB)
  std::uint32_t max_chunk_bytes = 256u << 20;  // one chunk, uncompressed (rosbag record: 768 KB)
};

// Ok when rosbag can open 'path' and read every message without leaving the file or a chunk;
// else an error "PATH: byte N: what is wrong" (N: the file offset of the record at fault, or of
// its chunk).
Status CheckBagStructure(const std::filesystem::path& path, const BagStructureLimits& limits = {});

}  // namespace semchain::ros1
