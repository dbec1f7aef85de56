#include "apps/closures_drawing.h"

#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>
#include <vector>

#include "drawing/png.h"

namespace semchain::app {
// Helpers in a namespace of their own: unity builds compile several files as one.
namespace {
namespace closures_png {

constexpr int kWidth = 900, kHeight = 700;
constexpr int kLeft = 90, kRight = 260, kTop = 60, kBottom = 80;  // margins around the plot

cv::Point ToPixel(double recall, double precision) {
  const double w = kWidth - kLeft - kRight, h = kHeight - kTop - kBottom;
  return {kLeft + static_cast<int>(recall * w + 0.5),
          kHeight - kBottom - static_cast<int>(precision * h + 0.5)};
}

void Text(cv::Mat& image, const std::string& text, cv::Point at, double scale = 0.5,
          const cv::Scalar& colour = {0, 0, 0}) {
  cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
}

std::string Fixed(double value, int digits) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.*f", digits, value);
  return buffer;
}

void DrawAxes(cv::Mat& image, const std::string& title) {
  const cv::Scalar grid(225, 225, 225), black(0, 0, 0);
  for (int k = 0; k <= 10; ++k) {
    const double v = 0.1 * k;
    cv::line(image, ToPixel(v, 0.0), ToPixel(v, 1.0), grid, 1);
    cv::line(image, ToPixel(0.0, v), ToPixel(1.0, v), grid, 1);
    if (k % 2 == 0) {
      Text(image, Fixed(v, 1), ToPixel(v, 0.0) + cv::Point(-12, 22));
      Text(image, Fixed(v, 1), ToPixel(0.0, v) + cv::Point(-40, 5));
    }
  }
  cv::rectangle(image, ToPixel(0.0, 1.0), ToPixel(1.0, 0.0), black, 1);
  Text(image, "recall (true candidates accepted / true candidates scored)",
       cv::Point(kLeft + 40, kHeight - 25));
  cv::Mat label(30, 260, CV_8UC3, cv::Scalar(255, 255, 255));
  Text(label, "precision", cv::Point(90, 20));
  cv::rotate(label, label, cv::ROTATE_90_COUNTERCLOCKWISE);
  label.copyTo(image(cv::Rect(15, kTop + 140, label.cols, label.rows)));
  Text(image, title, cv::Point(kLeft, 35), 0.6);
}

}  // namespace closures_png
}  // namespace

Status WritePrecisionRecallPng(const eval::ClosureTable& table, const std::string& title,
                               const std::filesystem::path& path) {
  cv::Mat image(closures_png::kHeight, closures_png::kWidth, CV_8UC3, cv::Scalar(255, 255, 255));
  closures_png::DrawAxes(image, title);
  struct Stage {
    const char* name;
    cv::Scalar colour;  // BGR
    const eval::StageCounts eval::ThresholdRow::*counts;
  };
  const Stage stages[] = {{"matcher score", {200, 120, 0}, &eval::ThresholdRow::scored},
                          {"after verification", {0, 140, 255}, &eval::ThresholdRow::verified},
                          {"after the back end", {40, 40, 200}, &eval::ThresholdRow::back_end}};
  for (std::size_t s = 0; s < std::size(stages); ++s) {
    const Stage& stage = stages[s];
    std::vector<cv::Point> points;
    std::vector<double> thresholds;
    for (const eval::ThresholdRow& row : table.rows) {
      const eval::StageCounts& counts = row.*stage.counts;
      if (!counts.precision || !counts.recall) continue;
      points.push_back(closures_png::ToPixel(*counts.recall, *counts.precision));
      thresholds.push_back(row.threshold);
    }
    for (std::size_t k = 0; k + 1 < points.size(); ++k) {
      cv::line(image, points[k], points[k + 1], stage.colour, 2, cv::LINE_AA);
    }
    std::optional<cv::Point> named;  // the last point whose threshold was written
    for (std::size_t k = 0; k < points.size(); ++k) {
      cv::circle(image, points[k], 4, stage.colour, cv::FILLED, cv::LINE_AA);
      // Thresholds named beside their points (offset by stage), unless on top of the last one
      // named: where the curve stands still only its first threshold is written.
      if (named && cv::norm(points[k] - *named) < 30.0) continue;
      closures_png::Text(image, closures_png::Fixed(thresholds[k], 2),
                         points[k] + cv::Point(6, -6 + 12 * static_cast<int>(s)), 0.35,
                         stage.colour);
      named = points[k];
    }
    const cv::Point legend(closures_png::kWidth - closures_png::kRight + 20,
                           closures_png::kTop + 30 + 28 * static_cast<int>(s));
    cv::line(image, legend, legend + cv::Point(30, 0), stage.colour, 2, cv::LINE_AA);
    closures_png::Text(image, stage.name, legend + cv::Point(38, 5), 0.5);
  }
  const cv::Point counts(closures_png::kWidth - closures_png::kRight + 20,
                         closures_png::kTop + 140);
  closures_png::Text(image, "candidates: " + std::to_string(table.candidates), counts, 0.45);
  closures_png::Text(image, "true: " + std::to_string(table.true_candidates),
                     counts + cv::Point(0, 22), 0.45);
  closures_png::Text(image, "false: " + std::to_string(table.false_candidates),
                     counts + cv::Point(0, 44), 0.45);
  closures_png::Text(image, "unlabelled: " + std::to_string(table.unlabelled),
                     counts + cv::Point(0, 66), 0.45);
  closures_png::Text(image, "points: score thresholds", counts + cv::Point(0, 100), 0.45);
  return drawing::WritePng(image, path);
}

}  // namespace semchain::app
