#include "apps/semantic_drawing.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <set>
#include <string>

#include "drawing/pixels.h"
#include "sim/world_drawing.h"

namespace semchain::app {
namespace {

constexpr drawing::Color kChainColor = {230, 0, 120};
constexpr drawing::Color kNeighbourColor = {150, 150, 150};

cv::Point Pixel(const drawing::TopDownCanvas& canvas, const Eigen::Vector2d& p) {
  const cv::Point2d px = canvas.ToPixel(p);
  return {static_cast<int>(std::lround(px.x)), static_cast<int>(std::lround(px.y))};
}

}  // namespace

void DrawSemanticMap(const semantic::SemanticMap& map, drawing::TopDownCanvas& canvas) {
  cv::Mat& image = canvas.image();
  for (const semantic::ChainLink& link : map.neighbours) {
    const semantic::SemanticObject* a = map.Find(link.from);
    const semantic::SemanticObject* b = map.Find(link.to);
    if (a && b)
      cv::line(image, Pixel(canvas, a->center), Pixel(canvas, b->center),
               drawing::Bgr(kNeighbourColor), 1, cv::LINE_AA);
  }
  if (!map.neighbours.empty()) {
    canvas.AddLegend("neighbour graph", kNeighbourColor, drawing::TopDownCanvas::Swatch::kLine);
  }
  std::set<std::string> legend;
  for (const semantic::SemanticObject& object : map.objects) {
    const auto it = std::find(map.classes.begin(), map.classes.end(), object.class_name);
    const drawing::Color color =
        sim::ClassColor(it == map.classes.end() ? -1 : static_cast<int>(it - map.classes.begin()));
    std::vector<cv::Point> polygon;
    for (const Eigen::Vector2d& p : object.footprint) polygon.push_back(Pixel(canvas, p));
    if (polygon.size() >= 3) {
      cv::fillPoly(image, std::vector<std::vector<cv::Point>>{polygon}, drawing::Bgr(color),
                   cv::LINE_AA);
      cv::polylines(image, polygon, true, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    }
    if (legend.insert(object.class_name).second) {
      canvas.AddLegend(object.class_name, color, drawing::TopDownCanvas::Swatch::kBox);
    }
  }
  for (const semantic::SemanticChain& chain : map.chains) {
    for (const semantic::ChainLink& link : chain.links) {
      const semantic::SemanticObject* a = map.Find(link.from);
      const semantic::SemanticObject* b = map.Find(link.to);
      if (!a || !b) continue;
      cv::arrowedLine(image, Pixel(canvas, a->center), Pixel(canvas, b->center),
                      drawing::Bgr(kChainColor), 2, cv::LINE_AA, 0,
                      std::min(0.3, 12.0 / std::max(1.0, link.distance * canvas.scale())));
    }
  }
  if (!map.chains.empty()) {
    canvas.AddLegend("semantic chain", kChainColor, drawing::TopDownCanvas::Swatch::kLine);
  }
  for (const semantic::SemanticObject& object : map.objects) {
    const cv::Point c = Pixel(canvas, object.center);
    cv::circle(image, c, 3, cv::Scalar(0, 0, 0), -1, cv::LINE_AA);
    cv::putText(image, std::to_string(object.id), c + cv::Point(5, -5), cv::FONT_HERSHEY_SIMPLEX,
                0.45, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
}

}  // namespace semchain::app
