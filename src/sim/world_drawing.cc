#include "sim/world_drawing.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/atomic_file.h"
#include "sensors/detection.h"
#include "sim/prism_silhouette.h"

namespace semchain::sim {
namespace {

constexpr int kShift = 4;  // OpenCV's fixed-point bits: sub-pixel accurate drawing
constexpr double kUnit = 1 << kShift;
constexpr Color kWallColor = {0, 0, 0};
constexpr Color kObstacleColor = {150, 150, 150};
constexpr Color kRouteColor = {40, 90, 220};
constexpr Color kTrialColor = {230, 140, 0};

cv::Scalar Bgr(const Color& c) { return cv::Scalar(c[2], c[1], c[0]); }

cv::Point Fixed(const cv::Point2d& p) {
  return cv::Point(static_cast<int>(std::lround(p.x * kUnit)),
                   static_cast<int>(std::lround(p.y * kUnit)));
}

std::vector<cv::Point> FixedPolygon(const std::vector<Eigen::Vector2d>& points,
                                    const TopDownCanvas& canvas) {
  std::vector<cv::Point> out;
  for (const Eigen::Vector2d& p : points) out.push_back(Fixed(canvas.ToPixel(p)));
  return out;
}

// An object built of parts: its footprint lightly tinted, the parts that stand on the floor
// (legs, bodies: what a low lidar meets) filled and the raised ones (tops, seats, screens)
// outlined, so a table shows as four legs under the outline of its top.
void DrawParts(const Solid& solid, const Color& color, TopDownCanvas& canvas) {
  Color tint;
  for (int c = 0; c < 3; ++c) tint[c] = static_cast<std::uint8_t>(255 - (255 - color[c]) * 0.3);
  cv::fillConvexPoly(canvas.image(), FixedPolygon(FootprintOutline(solid.footprint), canvas),
                     Bgr(tint), cv::LINE_AA, kShift);
  for (const Part& part : solid.parts) {
    const std::vector<cv::Point> polygon = FixedPolygon(FootprintOutline(part.footprint), canvas);
    if (part.bottom <= solid.base_height + 0.1) {
      cv::fillConvexPoly(canvas.image(), polygon, Bgr(color), cv::LINE_AA, kShift);
    } else {
      cv::polylines(canvas.image(), polygon, true, Bgr(color), 1, cv::LINE_AA, kShift);
    }
  }
}

void DrawSolid(const Solid& solid, const Color& color, TopDownCanvas& canvas) {
  if (solid.shape == ObjectShape::kParts && !solid.parts.empty()) {
    DrawParts(solid, color, canvas);
    return;
  }
  const std::vector<cv::Point> polygon = FixedPolygon(FootprintOutline(solid.footprint), canvas);
  cv::fillConvexPoly(canvas.image(), polygon, Bgr(color), cv::LINE_AA, kShift);
  // A thin solid (a door in its wall) would be all outline: only thicker ones get one.
  const Footprint& f = solid.footprint;
  const double thinnest =
      f.shape == Footprint::Shape::kCircle ? 2.0 * f.radius : std::min(f.width, f.depth);
  if (thinnest * canvas.scale() >= 6.0) {
    cv::polylines(canvas.image(), polygon, true, cv::Scalar(40, 40, 40), 1, cv::LINE_AA, kShift);
  }
}

// A dashed polyline: 10 px dashes with 6 px gaps, continuing across vertices.
void DrawDashed(const std::vector<Eigen::Vector2d>& points, const Color& color, bool closed,
                TopDownCanvas& canvas) {
  const double dash = 10.0, period = 16.0;
  double phase = 0.0;
  const std::size_t segments = closed ? points.size() : points.size() - 1;
  for (std::size_t i = 0; points.size() >= 2 && i < segments; ++i) {
    const cv::Point2d a = canvas.ToPixel(points[i]);
    const cv::Point2d b = canvas.ToPixel(points[(i + 1) % points.size()]);
    const double length = std::hypot(b.x - a.x, b.y - a.y);
    for (double s = 0.0; s < length;) {
      const double in_period = std::fmod(phase + s, period);
      const double step = in_period < dash ? dash - in_period : period - in_period;
      const double end = std::min(length, s + step);
      if (in_period < dash) {
        cv::line(canvas.image(), Fixed(a + (b - a) * (s / length)),
                 Fixed(a + (b - a) * (end / length)), Bgr(color), 2, cv::LINE_AA, kShift);
      }
      s = end;
    }
    phase = std::fmod(phase + length, period);
  }
}

}  // namespace

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

Bounds WorldBounds(const World& world) {
  Bounds bounds;
  for (const auto& wall : world.walls) {
    for (const Eigen::Vector2d& p : wall) bounds.Add(p);
  }
  for (const auto* solids : {&world.objects, &world.obstacles}) {
    for (const Solid& solid : *solids) {
      for (const Eigen::Vector2d& p : FootprintOutline(solid.footprint, 8)) bounds.Add(p);
    }
  }
  for (const Eigen::Vector2d& p : world.mapping_route) bounds.Add(p);
  for (const Eigen::Vector2d& p : world.trial_region) bounds.Add(p);
  return bounds;
}

Color ClassColor(int class_id) {
  static constexpr Color kPalette[] = {{140, 86, 75},   {31, 119, 180}, {214, 39, 40},
                                       {44, 160, 44},   {255, 127, 14}, {148, 103, 189},
                                       {227, 119, 194}, {23, 190, 207}, {188, 189, 34}};
  constexpr int kCount = static_cast<int>(std::size(kPalette));
  return class_id < 0 ? kObstacleColor : kPalette[class_id % kCount];
}

void DrawWorld(const World& world, TopDownCanvas& canvas) {
  const std::vector<std::string>& classes =
      world.classes.empty() ? DefaultClassNames() : world.classes;
  if (world.trial_region.size() >= 3) {
    const std::vector<cv::Point> region = FixedPolygon(world.trial_region, canvas);
    cv::polylines(canvas.image(), region, true, Bgr(kTrialColor), 2, cv::LINE_AA, kShift);
    canvas.AddLegend("trial region", kTrialColor, TopDownCanvas::Swatch::kLine);
  }
  // Walls first: doors stand in the wall line and must show over it.
  const int wall_px =
      std::max(2, static_cast<int>(std::lround(world.wall_thickness * canvas.scale())));
  for (const auto& wall : world.walls) {
    cv::polylines(canvas.image(), FixedPolygon(wall, canvas), false, Bgr(kWallColor), wall_px,
                  cv::LINE_AA, kShift);
  }
  if (!world.walls.empty()) canvas.AddLegend("wall", kWallColor, TopDownCanvas::Swatch::kLine);
  for (const Solid& solid : world.obstacles) DrawSolid(solid, kObstacleColor, canvas);
  if (!world.obstacles.empty()) {
    canvas.AddLegend("obstacle", kObstacleColor, TopDownCanvas::Swatch::kBox);
  }
  for (const Solid& solid : world.objects) {
    const auto it = std::find(classes.begin(), classes.end(), solid.class_name);
    const int id = it == classes.end() ? -1 : static_cast<int>(it - classes.begin());
    DrawSolid(solid, ClassColor(id), canvas);
    canvas.AddLegend(solid.class_name, ClassColor(id), TopDownCanvas::Swatch::kBox);
  }
  if (world.mapping_route.size() >= 2) {
    DrawDashed(world.mapping_route, kRouteColor, false, canvas);
    canvas.AddLegend("mapping route", kRouteColor, TopDownCanvas::Swatch::kDashed);
  }
}

void DrawGreyImage(const cv::Mat& grey, const Eigen::Vector2d& origin, double resolution,
                   TopDownCanvas& canvas) {
  // Each canvas pixel takes the image pixel under its centre (nearest neighbour: map cells
  // stay crisp at any scale).
  cv::Mat& image = canvas.image();
  const cv::Point2d top_left =
      canvas.ToPixel(origin + Eigen::Vector2d(0.0, grey.rows * resolution));
  const double cells_per_px = 1.0 / (resolution * canvas.scale());
  for (int y = 0; y < image.rows; ++y) {
    const int row = static_cast<int>(std::floor((y + 0.5 - top_left.y) * cells_per_px));
    if (row < 0 || row >= grey.rows) continue;
    for (int x = 0; x < image.cols; ++x) {
      const int col = static_cast<int>(std::floor((x + 0.5 - top_left.x) * cells_per_px));
      if (col < 0 || col >= grey.cols) continue;
      const std::uint8_t value = grey.at<std::uint8_t>(row, col);
      image.at<cv::Vec3b>(y, x) = cv::Vec3b(value, value, value);
    }
  }
}

void DrawTrajectory(const std::vector<Pose2>& poses, const Color& color, const std::string& label,
                    TopDownCanvas& canvas) {
  if (poses.empty()) return;
  std::vector<cv::Point> line;
  for (const Pose2& pose : poses) line.push_back(Fixed(canvas.ToPixel(pose.translation())));
  cv::polylines(canvas.image(), line, false, Bgr(color), 2, cv::LINE_AA, kShift);
  cv::circle(canvas.image(), line.front(), 5 << kShift, Bgr(color), -1, cv::LINE_AA, kShift);
  const Pose2& end = poses.back();
  const Eigen::Vector2d tip =
      end.translation() +
      (12.0 / canvas.scale()) * Eigen::Vector2d(std::cos(end.theta), std::sin(end.theta));
  cv::arrowedLine(canvas.image(), line.back(), Fixed(canvas.ToPixel(tip)), Bgr(color), 2,
                  cv::LINE_AA, kShift, 0.4);
  canvas.AddLegend(label, color, TopDownCanvas::Swatch::kLine);
}

void DrawPoints(const std::vector<Eigen::Vector2d>& points, const Color& color,
                const std::string& label, TopDownCanvas& canvas) {
  if (points.empty()) return;
  cv::Mat& image = canvas.image();
  const cv::Vec3b bgr(color[2], color[1], color[0]);
  for (const Eigen::Vector2d& p : points) {
    const cv::Point2d px = canvas.ToPixel(p);
    const int x = static_cast<int>(std::floor(px.x)), y = static_cast<int>(std::floor(px.y));
    if (x >= 0 && y >= 0 && x < image.cols && y < image.rows) image.at<cv::Vec3b>(y, x) = bgr;
  }
  canvas.AddLegend(label, color, TopDownCanvas::Swatch::kDot);
}

Status WritePng(const cv::Mat& bgr, const std::filesystem::path& path) {
  std::vector<std::uint8_t> bytes;
  if (!cv::imencode(".png", bgr, bytes)) {
    return Status::Error(path.string() + ": could not encode the image as PNG");
  }
  return WriteFileAtomically(
      path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace semchain::sim
