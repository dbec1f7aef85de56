#pragma once

#include <opencv2/core.hpp>

// YOLOv8's letterbox: the image is scaled to fit the network input without changing its aspect
// ratio and centred on a grey (114) canvas. Coordinates are pixel-edge coordinates (pixel u
// spans [u, u + 1)) in both images.
namespace semchain::detection {

inline constexpr int kLetterboxGrey = 114;

struct Letterbox {
  cv::Size image;   // the original image
  cv::Size input;   // the network input
  cv::Size scaled;  // the image's size inside the input
  int pad_left = 0;
  int pad_top = 0;

  // Input pixels per image pixel along x and y (equal up to the rounding of 'scaled').
  double scale_x() const { return double(scaled.width) / image.width; }
  double scale_y() const { return double(scaled.height) / image.height; }
  cv::Point2d ToInput(cv::Point2d image_point) const;
  cv::Point2d ToImage(cv::Point2d input_point) const;
};

// The letterbox that fits a non-empty 'image' into 'input': scale min(input / image) per axis,
// the scaled size rounded to whole pixels, the padding split evenly (an odd pixel goes to the
// right and bottom).
Letterbox FitLetterbox(cv::Size image, cv::Size input);

// 'image' resized (bilinear) and padded with grey as 'box' says; same type as 'image'.
cv::Mat ApplyLetterbox(const cv::Mat& image, const Letterbox& box);

}  // namespace semchain::detection
