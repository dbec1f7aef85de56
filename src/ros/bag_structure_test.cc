#include "ros/bag_structure.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace semchain::ros1 {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// The fuzz corpus's bags: four scans, tf, odometry and truth, written by `semchain bag export`
// (rosbag's C++ writer) uncompressed, with lz4 and with bz2; and ten scans with odometry in 11
// lz4 chunks written by Python's rosbag (chunk_threshold 1000).
std::string CorpusBag(const std::string& name) {
  std::ifstream in(fs::path(SEMCHAIN_SOURCE_DIR) / "fuzz/corpus/bag_import" / name,
                   std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class BagStructureTest : public ::testing::Test {
 protected:
  Status Check(const std::string& bytes, const BagStructureLimits& limits = {}) {
    const fs::path path = fs::temp_directory_path() /
                          ("semchain_bag_structure_" + std::to_string(::getpid()) + ".bag");
    std::ofstream(path, std::ios::binary) << bytes;
    const Status status = CheckBagStructure(path, limits);
    fs::remove(path);
    return status;
  }
  // Overwrites the 'size' bytes after the first 'field=' at or after 'from'.
  static void SetField(std::string* bytes, const std::string& field, std::size_t from,
                       std::uint64_t value, std::size_t size) {
    const std::size_t at = bytes->find(field + "=", from);
    ASSERT_NE(at, std::string::npos) << field;
    std::memcpy(bytes->data() + at + field.size() + 1, &value, size);
  }
};

TEST_F(BagStructureTest, BagsRosbagWroteAreWhole) {
  for (const char* name : {"four_scans.bag", "four_scans_lz4.bag", "four_scans_bz2.bag",
                           "python_rosbag_many_chunks_lz4.bag"}) {
    const std::string bag = CorpusBag(name);
    ASSERT_GT(bag.size(), 8192u) << name;
    EXPECT_TRUE(Check(bag).ok()) << name << ": " << Check(bag).message();
  }
}

TEST_F(BagStructureTest, AHeaderLongerThanTheLimitIsRefusedBeforeItIsRead) {
  std::string bag = CorpusBag("four_scans.bag");
  const std::uint32_t huge = 0x8A000000u;  // rosbag would allocate 2.3 GB for it
  std::memcpy(bag.data() + 13, &huge, 4);  // the bag header record's header length
  const Status status = Check(bag);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("byte 13: a record header of 2315255808 bytes"));
}

TEST_F(BagStructureTest, AChunkThatClaimsMoreThanTheLimitIsRefused) {
  std::string bag = CorpusBag("four_scans_lz4.bag");
  SetField(&bag, "size", 4096, 0xFFFFFFF0u, 4);
  const Status status = Check(bag);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("a chunk of 4294967280 bytes"));
}

TEST_F(BagStructureTest, AChunkSmallerThanItSaysIsRefused) {
  std::string bag = CorpusBag("four_scans.bag");
  const std::size_t size_field = bag.find("size=", 4096);
  ASSERT_NE(size_field, std::string::npos);
  std::uint32_t size = 0;
  std::memcpy(&size, bag.data() + size_field + 5, 4);
  SetField(&bag, "size", 4096, size + 8, 4);
  const Status status = Check(bag);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("says it holds " + std::to_string(size + 8)));
}

TEST_F(BagStructureTest, ChunkInfoPointingBesideAChunkIsRefused) {
  std::string bag = CorpusBag("four_scans_bz2.bag");
  SetField(&bag, "chunk_pos", 0, 13, 8);  // the bag header, not a chunk
  const Status status = Check(bag);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("chunk info points at byte 13, where no chunk starts"));
}

TEST_F(BagStructureTest, CorruptCompressedDataIsRefused) {
  for (const char* name : {"four_scans_lz4.bag", "four_scans_bz2.bag"}) {
    std::string bag = CorpusBag(name);
    // The first chunk's compressed data starts shortly after its header, past byte 4096.
    for (std::size_t i = 4200; i < 4400; ++i) bag[i] = static_cast<char>(bag[i] ^ 0x5A);
    EXPECT_FALSE(Check(bag).ok()) << name;
  }
}

TEST_F(BagStructureTest, ACutOffBagIsRefusedWherever) {
  const std::string bag = CorpusBag("four_scans.bag");
  for (std::size_t size : {std::size_t{5}, std::size_t{13}, std::size_t{20}, std::size_t{5000},
                           bag.size() / 2, bag.size() - 1}) {
    EXPECT_FALSE(Check(bag.substr(0, size)).ok()) << size;
  }
}

TEST_F(BagStructureTest, AnotherFileIsNotABag) {
  const Status status = Check("image: map.pgm\nresolution: 0.05\n");
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("not a readable ROS bag"));
}

}  // namespace
}  // namespace semchain::ros1
