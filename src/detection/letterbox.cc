#include "detection/letterbox.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "core/check.h"

namespace semchain::detection {

cv::Point2d Letterbox::ToInput(cv::Point2d image_point) const {
  return {image_point.x * scale_x() + pad_left, image_point.y * scale_y() + pad_top};
}

cv::Point2d Letterbox::ToImage(cv::Point2d input_point) const {
  return {(input_point.x - pad_left) / scale_x(), (input_point.y - pad_top) / scale_y()};
}

Letterbox FitLetterbox(cv::Size image, cv::Size input) {
  SEMCHAIN_CHECK(!image.empty() && !input.empty());
  const double scale =
      std::min(double(input.width) / image.width, double(input.height) / image.height);
  Letterbox box;
  box.image = image;
  box.input = input;
  box.scaled.width = std::clamp(int(std::lround(image.width * scale)), 1, input.width);
  box.scaled.height = std::clamp(int(std::lround(image.height * scale)), 1, input.height);
  box.pad_left = (input.width - box.scaled.width) / 2;
  box.pad_top = (input.height - box.scaled.height) / 2;
  return box;
}

cv::Mat ApplyLetterbox(const cv::Mat& image, const Letterbox& box) {
  SEMCHAIN_CHECK(image.size() == box.image);
  cv::Mat resized = image;
  if (box.scaled != box.image) cv::resize(image, resized, box.scaled, 0, 0, cv::INTER_LINEAR);
  cv::Mat canvas(box.input, image.type(), cv::Scalar::all(kLetterboxGrey));
  resized.copyTo(canvas(cv::Rect(cv::Point(box.pad_left, box.pad_top), box.scaled)));
  return canvas;
}

}  // namespace semchain::detection
