#pragma once

#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

// Test images for the tiny coloured-squares models of testdata/ (tools/make_tiny_yolo.py).
namespace semchain::detection::testing {

inline std::filesystem::path TestModel(const std::string& file) {
  return std::filesystem::path(SEMCHAIN_SOURCE_DIR) / "src/detection/testdata" / file;
}

inline const std::vector<std::string>& SquareClasses() {
  static const std::vector<std::string> kNames = {"red_square", "green_square", "blue_square"};
  return kNames;
}

struct Square {
  int class_id;
  cv::Rect rect;  // pixels; as a box [x, y, x + width, y + height) in pixel-edge coordinates
};

// Rectangles apart from each other, with even edges so that a 2x downscale keeps them sharp.
inline std::vector<Square> SceneSquares() {
  return {{0, cv::Rect(40, 48, 80, 64)},
          {1, cv::Rect(400, 60, 40, 140)},
          {2, cv::Rect(180, 300, 160, 120)},
          {0, cv::Rect(560, 380, 24, 24)}};
}

// Rectangles touching the image border, and one larger than the stride-8 anchors can reach
// (15 strides = 120 pixels from its centre at a 640-pixel input).
inline std::vector<Square> BorderSquares() {
  return {{0, cv::Rect(0, 0, 60, 40)},
          {1, cv::Rect(600, 400, 40, 80)},
          {2, cv::Rect(200, 80, 320, 260)},
          {0, cv::Rect(300, 440, 100, 40)}};
}

// A 640 x 480 RGB image of 'squares' in pure red, green and blue on a dark grey background.
inline cv::Mat SquareImage(const std::vector<Square>& squares, cv::Size size = {640, 480}) {
  cv::Mat rgb(size, CV_8UC3, cv::Scalar(60, 60, 60));
  for (const Square& square : squares) {
    cv::Scalar color(0, 0, 0);
    color[square.class_id] = 255;
    cv::rectangle(rgb, square.rect, color, cv::FILLED);
  }
  return rgb;
}

}  // namespace semchain::detection::testing
