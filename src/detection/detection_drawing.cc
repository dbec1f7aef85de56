#include "detection/detection_drawing.h"

#include <algorithm>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <string>

namespace semchain::detection {
namespace {

// Well-separated colours (RGB) for class ids, repeating after ten.
cv::Scalar ClassColor(int class_id) {
  static const cv::Scalar kPalette[] = {
      {230, 25, 75},  {60, 180, 75},  {0, 130, 200},  {245, 130, 48}, {145, 30, 180},
      {70, 240, 240}, {240, 50, 230}, {210, 245, 60}, {128, 0, 0},    {0, 0, 128}};
  const int count = int(sizeof(kPalette) / sizeof(kPalette[0]));
  return kPalette[((class_id % count) + count) % count];
}

std::string Label(const Detection& detection) {
  char text[96];
  if (detection.score < 0.0) return detection.class_name;  // a truth box: no score
  if (detection.depth_m > 0.0) {
    std::snprintf(text, sizeof(text), "%s %.2f %.2fm", detection.class_name.c_str(),
                  detection.score, detection.depth_m);
  } else {
    std::snprintf(text, sizeof(text), "%s %.2f", detection.class_name.c_str(), detection.score);
  }
  return text;
}

}  // namespace

cv::Mat DrawDetections(const cv::Mat& image, const std::vector<Detection>& detections) {
  cv::Mat canvas = image.clone();
  const int thickness = std::max(1, std::min(image.cols, image.rows) / 240);
  const double font_scale = 0.4 * thickness;
  for (const Detection& detection : detections) {
    const cv::Scalar color = ClassColor(detection.class_id);
    // Boxes are in pixel-edge coordinates; the outline runs along the outermost pixels.
    const cv::Point top_left(int(detection.box[0]), int(detection.box[1]));
    const cv::Point bottom_right(int(detection.box[2]) - 1, int(detection.box[3]) - 1);
    cv::rectangle(canvas, top_left, bottom_right, color, thickness);
    const std::string label = Label(detection);
    int baseline = 0;
    const cv::Size text =
        cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, font_scale, thickness, &baseline);
    // The label sits above the box, or inside it at the top edge, and within the image.
    const int y = top_left.y - text.height - baseline >= 0 ? top_left.y : top_left.y + text.height;
    const int x = std::max(0, std::min(top_left.x, canvas.cols - text.width));
    cv::rectangle(canvas, cv::Point(x, y - text.height - baseline), cv::Point(x + text.width, y),
                  color, cv::FILLED);
    cv::putText(canvas, label, cv::Point(x, y - baseline), cv::FONT_HERSHEY_SIMPLEX, font_scale,
                cv::Scalar(255, 255, 255), thickness, cv::LINE_AA);
  }
  return canvas;
}

}  // namespace semchain::detection
