#include "bow/bow_vocabulary_io.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>

#include "bow/bow_testing.h"
#include "core/atomic_file.h"

namespace semchain::bow {
namespace {

namespace fs = std::filesystem;

Vocabulary SmallVocabulary() {
  std::vector<cv::Mat> images;
  for (int i = 0; i < 10; ++i) {
    images.push_back(testing::RandomDescriptors(60, static_cast<std::uint64_t>(i)));
  }
  VocabularyOptions options;
  options.branching = 4;
  options.levels = 3;
  Result<Vocabulary> vocabulary = Vocabulary::Train(images, options);
  EXPECT_TRUE(vocabulary.ok());
  return *vocabulary;
}

// The message of a parse that must fail.
std::string ParseError(const std::string& bytes) {
  const Result<Vocabulary> parsed = ParseVocabulary(bytes, "v.bin");
  EXPECT_FALSE(parsed.ok());
  return parsed.ok() ? "" : parsed.status().message();
}

TEST(VocabularyIoTest, RoundTripKeepsTreeWeightsAndWords) {
  const Vocabulary original = SmallVocabulary();
  const fs::path path =
      fs::temp_directory_path() / ("semchain_vocab_" + std::to_string(::getpid()) + ".bin");
  ASSERT_TRUE(WriteVocabulary(path, original).ok());
  const Result<Vocabulary> loaded = ReadVocabulary(path);
  fs::remove(path);
  ASSERT_TRUE(loaded.ok()) << loaded.status().message();
  EXPECT_EQ(loaded->branching(), 4);
  EXPECT_EQ(loaded->levels(), 3);
  EXPECT_EQ(loaded->data().training_images, 10);
  EXPECT_EQ(loaded->data().parent, original.data().parent);
  EXPECT_EQ(loaded->data().word, original.data().word);
  EXPECT_EQ(loaded->data().weight, original.data().weight);
  EXPECT_EQ(cv::norm(loaded->data().descriptors, original.data().descriptors, cv::NORM_HAMMING),
            0.0);
  const cv::Mat query = testing::RandomDescriptors(50, 99);
  EXPECT_EQ(loaded->Transform(query), original.Transform(query));
}

TEST(VocabularyIoTest, TruncatedFileIsAnError) {
  const std::string bytes = SerializeVocabulary(SmallVocabulary());
  EXPECT_NE(ParseError(bytes.substr(0, bytes.size() - 100)).find("v.bin: truncated"),
            std::string::npos);
  EXPECT_NE(ParseError(bytes.substr(0, 12)).find("v.bin: truncated header"), std::string::npos);
  EXPECT_NE(ParseError("").find("not a semchain vocabulary"), std::string::npos);
}

TEST(VocabularyIoTest, CorruptFileIsAnError) {
  std::string bytes = SerializeVocabulary(SmallVocabulary());
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x5A);
  EXPECT_NE(ParseError(bytes).find("checksum mismatch"), std::string::npos);
  EXPECT_NE(ParseError("GARBAGE! this is not a vocabulary").find("no SCBOWVOC header"),
            std::string::npos);
}

TEST(VocabularyIoTest, MismatchedVersionOrDescriptorSizeIsAnError) {
  const std::string good = SerializeVocabulary(SmallVocabulary());
  std::string version = good;
  version[8] = 7;  // u32 version after the 8-byte magic
  EXPECT_NE(ParseError(version).find("version 7, expected 1"), std::string::npos);
  std::string descriptor = good;
  descriptor[8 + 12] = 64;  // u32 descriptor bytes
  EXPECT_NE(ParseError(descriptor).find("descriptors of 64 bytes, expected 32"), std::string::npos);
}

TEST(VocabularyIoTest, MissingFileNamesIt) {
  const Result<Vocabulary> missing = ReadVocabulary("/nonexistent/vocab.bin");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.status().message().find("/nonexistent/vocab.bin"), std::string::npos);
}

}  // namespace
}  // namespace semchain::bow
