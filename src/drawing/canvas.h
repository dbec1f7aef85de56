#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/status.h"

// A top-down canvas in world metres (x right, y up) with a legend beside it: what `semchain
// render`, the semantic map's picture and the relocalization pictures are drawn on.
namespace semchain::drawing {

using Color = std::array<std::uint8_t, 3>;  // RGB

struct DrawingOptions {
  double pixels_per_meter = 50.0;
  int margin_px = 20;         // white border around the drawn region
  int legend_width_px = 170;  // panel right of the drawing; 0 = no legend
  int max_side_px = 16000;    // larger images are refused (lower pixels_per_meter)
};

// An axis-aligned region of the plane, metres.
struct Bounds {
  Eigen::Vector2d min{1e300, 1e300};
  Eigen::Vector2d max{-1e300, -1e300};
  void Add(const Eigen::Vector2d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  bool empty() const { return min.x() > max.x(); }
};

class TopDownCanvas {
 public:
  // A white canvas showing 'bounds'; an error when it would be empty or too large.
  static Result<TopDownCanvas> Create(const Bounds& bounds, const DrawingOptions& options);

  // The pixel of world point 'p' (sub-pixel, for OpenCV's shifted drawing calls).
  cv::Point2d ToPixel(const Eigen::Vector2d& p) const;
  double scale() const { return options_.pixels_per_meter; }
  cv::Mat& image() { return image_; }  // BGR, without the legend panel

  // Adds a legend line: a swatch in 'color' drawn as a filled box, a line or a dot.
  enum class Swatch { kBox, kLine, kDashed, kDot };
  void AddLegend(const std::string& label, const Color& color, Swatch swatch);

  // The drawing with its legend panel (BGR).
  cv::Mat Compose() const;

 private:
  struct LegendEntry {
    std::string label;
    Color color;
    Swatch swatch;
  };
  TopDownCanvas(const Bounds& bounds, const DrawingOptions& options, cv::Size size);

  Bounds bounds_;
  DrawingOptions options_;
  cv::Mat image_;
  std::vector<LegendEntry> legend_;
};

}  // namespace semchain::drawing
