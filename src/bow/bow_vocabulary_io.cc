#include "bow/bow_vocabulary_io.h"

#include <cstdint>
#include <cstring>

#include "core/atomic_file.h"

namespace semchain::bow {
namespace {

constexpr char kMagic[8] = {'S', 'C', 'B', 'O', 'W', 'V', 'O', 'C'};
constexpr std::size_t kHeaderBytes = 8 + 6 * 4;
constexpr std::size_t kNodeBytes = 4 + 4 + 8 + kOrbDescriptorBytes;
constexpr std::size_t kHashBytes = 8;

std::uint64_t Fnv1a(const char* data, std::size_t size) {
  std::uint64_t hash = 14695981039346656037ull;
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= static_cast<unsigned char>(data[i]);
    hash *= 1099511628211ull;
  }
  return hash;
}

// Fixed-width values copied byte for byte: the build targets are little-endian (x86-64,
// aarch64), which is the file's byte order.
template <typename T>
void Put(std::string* out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out->append(bytes, sizeof(T));
}

template <typename T>
T Get(const std::string& in, std::size_t* offset) {
  T value;
  std::memcpy(&value, in.data() + *offset, sizeof(T));
  *offset += sizeof(T);
  return value;
}

}  // namespace

std::string SerializeVocabulary(const Vocabulary& vocabulary) {
  const VocabularyData& data = vocabulary.data();
  std::string out(kMagic, sizeof(kMagic));
  Put<std::uint32_t>(&out, kVocabularyFileVersion);
  Put<std::uint32_t>(&out, static_cast<std::uint32_t>(data.branching));
  Put<std::uint32_t>(&out, static_cast<std::uint32_t>(data.levels));
  Put<std::uint32_t>(&out, static_cast<std::uint32_t>(kOrbDescriptorBytes));
  Put<std::uint32_t>(&out, static_cast<std::uint32_t>(data.training_images));
  Put<std::uint32_t>(&out, static_cast<std::uint32_t>(data.parent.size()));
  for (std::size_t i = 0; i < data.parent.size(); ++i) {
    Put<std::int32_t>(&out, data.parent[i]);
    Put<std::int32_t>(&out, data.word[i]);
    Put<double>(&out, data.weight[i]);
    out.append(reinterpret_cast<const char*>(data.descriptors.ptr(static_cast<int>(i))),
               kOrbDescriptorBytes);
  }
  Put<std::uint64_t>(&out, Fnv1a(out.data(), out.size()));
  return out;
}

Status WriteVocabulary(const std::filesystem::path& path, const Vocabulary& vocabulary) {
  return WriteFileAtomically(path, SerializeVocabulary(vocabulary));
}

Result<Vocabulary> ParseVocabulary(const std::string& bytes, const std::string& source) {
  const auto error = [&](const std::string& what) { return Status::Error(source + ": " + what); };
  if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) {
    return error("not a semchain vocabulary file (no SCBOWVOC header)");
  }
  if (bytes.size() < kHeaderBytes) return error("truncated header");
  std::size_t offset = sizeof(kMagic);
  const std::uint32_t version = Get<std::uint32_t>(bytes, &offset);
  if (version != kVocabularyFileVersion) {
    return error("vocabulary file version " + std::to_string(version) + ", expected " +
                 std::to_string(kVocabularyFileVersion));
  }
  VocabularyData data;
  data.branching = static_cast<int>(Get<std::uint32_t>(bytes, &offset));
  data.levels = static_cast<int>(Get<std::uint32_t>(bytes, &offset));
  const std::uint32_t descriptor_bytes = Get<std::uint32_t>(bytes, &offset);
  data.training_images = static_cast<int>(Get<std::uint32_t>(bytes, &offset));
  const std::uint64_t nodes = Get<std::uint32_t>(bytes, &offset);
  if (descriptor_bytes != kOrbDescriptorBytes) {
    return error("descriptors of " + std::to_string(descriptor_bytes) + " bytes, expected " +
                 std::to_string(kOrbDescriptorBytes) + " (ORB)");
  }
  const std::uint64_t expected = kHeaderBytes + nodes * kNodeBytes + kHashBytes;
  if (bytes.size() != expected) {
    return error((bytes.size() < expected ? "truncated (" : "trailing bytes (") +
                 std::to_string(bytes.size()) + " bytes, expected " + std::to_string(expected) +
                 " for " + std::to_string(nodes) + " nodes)");
  }
  std::size_t hash_offset = bytes.size() - kHashBytes;
  if (Get<std::uint64_t>(bytes, &hash_offset) != Fnv1a(bytes.data(), bytes.size() - kHashBytes)) {
    return error("checksum mismatch (corrupt file)");
  }
  data.descriptors = cv::Mat(static_cast<int>(nodes), kOrbDescriptorBytes, CV_8UC1);
  for (std::uint64_t i = 0; i < nodes; ++i) {
    data.parent.push_back(Get<std::int32_t>(bytes, &offset));
    data.word.push_back(Get<std::int32_t>(bytes, &offset));
    data.weight.push_back(Get<double>(bytes, &offset));
    std::memcpy(data.descriptors.ptr(static_cast<int>(i)), bytes.data() + offset,
                kOrbDescriptorBytes);
    offset += kOrbDescriptorBytes;
  }
  Result<Vocabulary> vocabulary = Vocabulary::FromData(std::move(data));
  if (!vocabulary.ok()) return vocabulary.status().WithContext(source);
  return vocabulary;
}

Result<Vocabulary> ReadVocabulary(const std::filesystem::path& path) {
  Result<std::string> bytes = ReadFile(path);
  if (!bytes.ok()) return bytes.status();
  return ParseVocabulary(*bytes, path.string());
}

}  // namespace semchain::bow
