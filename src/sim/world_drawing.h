#pragma once

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "core/status.h"
#include "sim/world.h"

// Top-down drawings of worlds, runs and maps (`semchain render`): a canvas in world metres
// (x right, y up) that the CLI composes from the pieces below, with a legend beside it.
namespace semchain::sim {

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

// The region covered by the world's walls, solids, route and trial region.
Bounds WorldBounds(const World& world);

// The colour of class 'class_id' (a fixed palette; -1 and unknown classes are grey).
Color ClassColor(int class_id);

// Draws walls (black), semantic objects (filled with their class colour, legend by class),
// obstacles (grey), the mapping route (dashed) and the trial region (outline).
void DrawWorld(const World& world, TopDownCanvas& canvas);

// Draws a greyscale image (row 0 at the top, e.g. an occupancy map) whose lower-left corner is
// at 'origin' and whose pixels are 'resolution' metres wide, under whatever is drawn later.
void DrawGreyImage(const cv::Mat& grey, const Eigen::Vector2d& origin, double resolution,
                   TopDownCanvas& canvas);

// Draws a trajectory as a line through its positions, a dot at its start and an arrow at its
// end pose, with a legend entry 'label'.
void DrawTrajectory(const std::vector<Pose2>& poses, const Color& color, const std::string& label,
                    TopDownCanvas& canvas);

// Draws points (e.g. laser returns in the world frame) as small dots.
void DrawPoints(const std::vector<Eigen::Vector2d>& points, const Color& color,
                const std::string& label, TopDownCanvas& canvas);

// Writes 'bgr' as a PNG, atomically.
Status WritePng(const cv::Mat& bgr, const std::filesystem::path& path);

}  // namespace semchain::sim
