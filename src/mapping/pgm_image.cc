#include "mapping/pgm_image.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <system_error>

#include "core/atomic_file.h"
#include "core/check.h"

namespace semchain::mapping {
namespace {

// Reads the next header token of a PGM, skipping whitespace and '#' comments.
bool NextToken(const std::string& data, std::size_t* pos, std::string* token) {
  token->clear();
  while (*pos < data.size()) {
    const char c = data[*pos];
    if (c == '#') {
      while (*pos < data.size() && data[*pos] != '\n') ++*pos;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++*pos;
    } else {
      break;
    }
  }
  while (*pos < data.size() && !std::isspace(static_cast<unsigned char>(data[*pos]))) {
    token->push_back(data[(*pos)++]);
  }
  return !token->empty();
}

bool ParseInt(const std::string& token, int minimum, int* value) {
  const char* end = token.data() + token.size();
  const auto result = std::from_chars(token.data(), end, *value);
  return result.ec == std::errc() && result.ptr == end && *value >= minimum;
}
bool ParsePositive(const std::string& token, int* value) { return ParseInt(token, 1, value); }

Result<GrayImage> ParsePgm(const std::string& data, const std::filesystem::path& path) {
  const auto error = [&path](const std::string& what) {
    return Status::Error(path.string() + ": " + what);
  };
  std::size_t pos = 2;
  std::string token;
  int width = 0, height = 0, maxval = 0;
  if (!NextToken(data, &pos, &token) || !ParsePositive(token, &width) ||
      !NextToken(data, &pos, &token) || !ParsePositive(token, &height) ||
      !NextToken(data, &pos, &token) || !ParsePositive(token, &maxval) || maxval > 255) {
    return error("malformed PGM header (need width, height and maxval <= 255)");
  }
  GrayImage image{width, height, {}};
  const std::size_t count = static_cast<std::size_t>(width) * height;
  if (count > kMaxImagePixels) {
    return error("PGM of " + std::to_string(width) + " x " + std::to_string(height) +
                 " pixels is larger than the " + std::to_string(kMaxImagePixels / 1000000) +
                 " million pixels a map may have");
  }
  // Check the data is there before allocating for it: the header alone may ask for gigabytes.
  const bool binary = data[1] == '5';
  if (binary ? data.size() < pos + 1 + count : (data.size() - pos) / 2 < count) {
    return error("PGM pixel data truncated (the header asks for " + std::to_string(width) + " x " +
                 std::to_string(height) + " pixels)");
  }
  image.pixels.reserve(count);
  if (binary) {
    ++pos;  // exactly one whitespace byte after maxval
    for (std::size_t i = 0; i < count; ++i) {
      image.pixels.push_back(static_cast<std::uint8_t>(data[pos + i]));
    }
  } else {
    for (std::size_t i = 0; i < count; ++i) {
      int value = 0;
      if (!NextToken(data, &pos, &token) || !ParseInt(token, 0, &value) || value > maxval) {
        return error("PGM pixel data truncated or malformed");
      }
      image.pixels.push_back(value);
    }
  }
  if (maxval != 255) {
    for (double& p : image.pixels) p = std::round(p * 255.0 / maxval);
  }
  return image;
}

Result<GrayImage> DecodeWithOpenCv(const std::string& data, const std::filesystem::path& path) {
  if (data.empty()) return Status::Error(path.string() + ": empty image file");
  const std::vector<std::uint8_t> bytes(data.begin(), data.end());
  cv::Mat decoded;
  try {
    decoded = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception&) {  // OpenCV's decoders throw on some corrupt files
    decoded = cv::Mat();
  }
  if (decoded.empty() || decoded.depth() != CV_8U) {
    return Status::Error(path.string() + ": cannot decode image (need 8-bit PGM, PNG, ...)");
  }
  if (static_cast<std::size_t>(decoded.cols) * decoded.rows > kMaxImagePixels) {
    return Status::Error(path.string() + ": image of " + std::to_string(decoded.cols) + " x " +
                         std::to_string(decoded.rows) + " pixels is larger than a map may be");
  }
  const int channels = std::min(decoded.channels(), 3);  // alpha is not part of the mean
  GrayImage image{decoded.cols, decoded.rows, {}};
  image.pixels.reserve(static_cast<std::size_t>(decoded.cols) * decoded.rows);
  for (int row = 0; row < decoded.rows; ++row) {
    const std::uint8_t* line = decoded.ptr<std::uint8_t>(row);
    for (int x = 0; x < decoded.cols; ++x) {
      double sum = 0.0;
      for (int c = 0; c < channels; ++c) sum += line[x * decoded.channels() + c];
      image.pixels.push_back(sum / channels);
    }
  }
  return image;
}

}  // namespace

Result<GrayImage> ReadGrayImage(const std::filesystem::path& path) {
  // A map.yaml names its image: one naming /dev/zero or a pipe would read forever.
  std::error_code error;
  if (std::filesystem::exists(path, error) && !std::filesystem::is_regular_file(path, error)) {
    return Status::Error(path.string() + ": not a regular file");
  }
  const Result<std::string> data = ReadFile(path);
  if (!data.ok()) return data.status();
  if (data->size() >= 2 && (*data)[0] == 'P' && ((*data)[1] == '5' || (*data)[1] == '2')) {
    return ParsePgm(*data, path);
  }
  return DecodeWithOpenCv(*data, path);
}

namespace {

std::string PgmHeader(int width, int height, double resolution) {
  std::ostringstream header;
  header << "P5\n# CREATOR: semchain " << resolution << " m/pix\n"
         << width << " " << height << "\n255\n";
  return header.str();
}

}  // namespace

Status WritePgm(const std::filesystem::path& path, const GrayImage& image, double resolution) {
  std::string bytes = PgmHeader(image.width, image.height, resolution);
  bytes.reserve(bytes.size() + image.pixels.size());
  for (const double p : image.pixels) {
    bytes.push_back(static_cast<char>(std::clamp<long>(std::lround(p), 0, 255)));
  }
  return WriteFileAtomically(path, bytes);
}

Status WritePgm(const std::filesystem::path& path, int width, int height,
                std::span<const std::uint8_t> pixels, double resolution) {
  SEMCHAIN_CHECK(pixels.size() == static_cast<std::size_t>(width) * height);
  std::string bytes = PgmHeader(width, height, resolution);
  bytes.append(reinterpret_cast<const char*>(pixels.data()), pixels.size());
  return WriteFileAtomically(path, bytes);
}

}  // namespace semchain::mapping
