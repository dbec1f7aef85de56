#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "core/status.h"

// YOLO label files (DESIGN.md §5.6): one line per object, "class cx cy w h", the box's centre
// and size normalised to the image.
namespace semchain {

struct YoloLabel {
  int class_id = 0;
  double cx = 0.0, cy = 0.0, w = 0.0, h = 0.0;  // fractions of the image width / height

  // The box [x1, y1, x2, y2] in pixels of a width × height image.
  std::array<double, 4> PixelBox(int width, int height) const {
    return {(cx - 0.5 * w) * width, (cy - 0.5 * h) * height, (cx + 0.5 * w) * width,
            (cy + 0.5 * h) * height};
  }
};

// Parses 'text' (named 'source' in errors); a class id outside [0, class_count), a number that
// is not finite or lies outside [0, 1], a box reaching outside the image or a line without five
// fields is an error naming the line ("labels/train/a.txt:3: class 12 out of range (nc 10)").
Result<std::vector<YoloLabel>> ParseYoloLabels(const std::string& text, const std::string& source,
                                               int class_count);
Result<std::vector<YoloLabel>> ReadYoloLabels(const std::filesystem::path& path, int class_count);

}  // namespace semchain
