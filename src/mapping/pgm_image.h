#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "core/status.h"

// The greyscale images behind map_server maps.
namespace semchain::mapping {

struct GrayImage {
  int width = 0;
  int height = 0;
  // Row-major from the top row; for colour images the mean of the channels (as map_server).
  std::vector<double> pixels;
};

// The most pixels a map image may have: 100 million (a 500 m × 500 m floor at 5 cm; the MIT
// Killian map has 25 million). A header asking for more is refused before anything is allocated.
inline constexpr std::size_t kMaxImagePixels = 100'000'000;

// Reads a binary (P5) or ASCII (P2) PGM with maxval <= 255 with our own parser (exact), and
// anything else OpenCV can decode (PNG, BMP…). Alpha channels are ignored.
Result<GrayImage> ReadGrayImage(const std::filesystem::path& path);

// Writes a binary PGM atomically ("P5", a comment with the resolution, maxval 255); pixel
// values are rounded to 0..255.
Status WritePgm(const std::filesystem::path& path, const GrayImage& image, double resolution);

// The same from 8-bit pixels (row-major from the top row), as the map writer has them: a campus
// map of 25 million cells takes 25 MB so, 200 MB as a GrayImage's doubles.
Status WritePgm(const std::filesystem::path& path, int width, int height,
                std::span<const std::uint8_t> pixels, double resolution);

}  // namespace semchain::mapping
