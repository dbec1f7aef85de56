#include "sim/world_drawing.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "drawing/pixels.h"
#include "sensors/detection.h"
#include "sim/prism_silhouette.h"

namespace semchain::sim {
namespace {

using drawing::Bgr;
using drawing::Color;
using drawing::Fixed;
using drawing::kShift;
using drawing::TopDownCanvas;

constexpr Color kWallColor = {0, 0, 0};
constexpr Color kObstacleColor = {150, 150, 150};
constexpr Color kRouteColor = {40, 90, 220};
constexpr Color kTrialColor = {230, 140, 0};

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

drawing::Bounds WorldBounds(const World& world) {
  drawing::Bounds bounds;
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

drawing::Color ClassColor(int class_id) {
  static constexpr Color kPalette[] = {{140, 86, 75},   {31, 119, 180}, {214, 39, 40},
                                       {44, 160, 44},   {255, 127, 14}, {148, 103, 189},
                                       {227, 119, 194}, {23, 190, 207}, {188, 189, 34}};
  constexpr int kCount = static_cast<int>(std::size(kPalette));
  return class_id < 0 ? kObstacleColor : kPalette[class_id % kCount];
}

void DrawWorld(const World& world, drawing::TopDownCanvas& canvas) {
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

}  // namespace semchain::sim
