#include "drawing/canvas.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "drawing/pixels.h"

namespace semchain::drawing {

Result<TopDownCanvas> TopDownCanvas::Create(const Bounds& bounds, const DrawingOptions& options) {
  if (bounds.empty()) return Status::Error("nothing to draw");
  if (!(options.pixels_per_meter > 0.0)) return Status::Error("the scale must be positive");
  const Eigen::Vector2d extent = (bounds.max - bounds.min) * options.pixels_per_meter;
  const double width = std::ceil(extent.x()) + 2 * options.margin_px + 1;
  const double height = std::ceil(extent.y()) + 2 * options.margin_px + 1;
  if (width > options.max_side_px || height > options.max_side_px) {
    return Status::Error("the image would be " + std::to_string(std::lround(width)) + " x " +
                         std::to_string(std::lround(height)) +
                         " pixels; lower the scale (pixels per metre)");
  }
  return TopDownCanvas(bounds, options,
                       cv::Size(static_cast<int>(width), static_cast<int>(height)));
}

TopDownCanvas::TopDownCanvas(const Bounds& bounds, const DrawingOptions& options, cv::Size size)
    : bounds_(bounds), options_(options), image_(size, CV_8UC3, cv::Scalar(255, 255, 255)) {}

cv::Point2d TopDownCanvas::ToPixel(const Eigen::Vector2d& p) const {
  const double s = options_.pixels_per_meter;
  return {options_.margin_px + (p.x() - bounds_.min.x()) * s,
          options_.margin_px + (bounds_.max.y() - p.y()) * s};
}

void TopDownCanvas::AddLegend(const std::string& label, const Color& color, Swatch swatch) {
  for (const LegendEntry& entry : legend_) {
    if (entry.label == label) return;
  }
  legend_.push_back({label, color, swatch});
}

cv::Mat TopDownCanvas::Compose() const {
  if (options_.legend_width_px <= 0 || legend_.empty()) return image_.clone();
  const int rows = std::max(image_.rows, 20 * static_cast<int>(legend_.size()) + 20);
  cv::Mat out(rows, image_.cols + options_.legend_width_px, CV_8UC3, cv::Scalar(255, 255, 255));
  image_.copyTo(out(cv::Rect(0, 0, image_.cols, image_.rows)));
  for (std::size_t i = 0; i < legend_.size(); ++i) {
    const LegendEntry& e = legend_[i];
    const int x = image_.cols + 8, y = 20 + 20 * static_cast<int>(i);
    const cv::Scalar color = Bgr(e.color);
    if (e.swatch == Swatch::kBox) cv::rectangle(out, {x, y - 10}, {x + 18, y + 2}, color, -1);
    if (e.swatch == Swatch::kLine) cv::line(out, {x, y - 4}, {x + 18, y - 4}, color, 2);
    if (e.swatch == Swatch::kDashed) {
      cv::line(out, {x, y - 4}, {x + 6, y - 4}, color, 2);
      cv::line(out, {x + 11, y - 4}, {x + 18, y - 4}, color, 2);
    }
    if (e.swatch == Swatch::kDot) cv::circle(out, {x + 9, y - 4}, 3, color, -1);
    cv::putText(out, e.label, {x + 26, y}, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 1,
                cv::LINE_AA);
  }
  return out;
}

}  // namespace semchain::drawing
