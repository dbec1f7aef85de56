#include "apps/track_drawing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "drawing/png.h"

namespace semchain::app {
namespace {

constexpr int kWidthPx = 1200;
constexpr int kPanelHeightPx = 280;
constexpr int kLeftPx = 70;
constexpr int kRightPx = 20;
constexpr int kTopPx = 40;                 // room for the title
constexpr int kGapPx = 40;                 // between the panels, room for the axis labels
const cv::Scalar kErrorColor(200, 80, 0);  // BGR: blue
const cv::Scalar kReferenceColor(170, 170, 170);
const cv::Scalar kTargetColor(40, 40, 220);  // red
const cv::Scalar kAxisColor(0, 0, 0);

std::string Number(double value, int digits) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.*f", digits, value);
  return text;
}

// One panel: a curve of 'values' (and 'reference' in grey) over 'times', y from 0 to a scale
// that shows the target and most of the curve (values above it are drawn on the top edge).
class Panel {
 public:
  Panel(cv::Mat* image, int top, double t_end, double y_max)
      : image_(image), top_(top), t_end_(std::max(t_end, 1e-9)), y_max_(y_max) {}

  cv::Point At(double t, double y) const {
    const double fx = t / t_end_;
    const double fy = std::clamp(y / y_max_, 0.0, 1.0);
    return {kLeftPx + static_cast<int>(std::lround(fx * (kWidthPx - kLeftPx - kRightPx))),
            top_ + kPanelHeightPx - static_cast<int>(std::lround(fy * kPanelHeightPx))};
  }

  void Curve(const std::vector<double>& times, const std::vector<double>& values,
             const cv::Scalar& color) const {
    for (std::size_t i = 1; i < times.size(); ++i) {
      cv::line(*image_, At(times[i - 1], values[i - 1]), At(times[i], values[i]), color, 1,
               cv::LINE_AA);
    }
  }

  void Target(double y) const {
    for (double t = 0.0; t < t_end_; t += t_end_ / 120.0) {
      cv::line(*image_, At(t, y), At(std::min(t_end_, t + t_end_ / 240.0), y), kTargetColor, 1);
    }
  }

  void Axes(const std::string& label, int digits) const {
    cv::rectangle(*image_, At(0.0, y_max_), At(t_end_, 0.0), kAxisColor, 1);
    for (int k = 0; k <= 4; ++k) {
      const double y = y_max_ * k / 4.0;
      cv::putText(*image_, Number(y, digits), At(0.0, y) + cv::Point(-62, 4),
                  cv::FONT_HERSHEY_SIMPLEX, 0.4, kAxisColor, 1, cv::LINE_AA);
    }
    for (int k = 0; k <= 10; ++k) {
      const double t = t_end_ * k / 10.0;
      cv::putText(*image_, Number(t, 0), At(t, 0.0) + cv::Point(-8, 16), cv::FONT_HERSHEY_SIMPLEX,
                  0.4, kAxisColor, 1, cv::LINE_AA);
    }
    cv::putText(*image_, label, At(0.0, y_max_) + cv::Point(6, 16), cv::FONT_HERSHEY_SIMPLEX, 0.5,
                kAxisColor, 1, cv::LINE_AA);
  }

 private:
  cv::Mat* image_;
  int top_;
  double t_end_, y_max_;
};

// A scale that shows the target twice over and the 99th percentile of the curve.
double Scale(const std::vector<double>& values, double target) {
  return std::max(2.0 * target, 1.1 * eval::Percentile(values, 99.0));
}

}  // namespace

Status WriteTrackPng(const std::string& title, const std::vector<eval::TrackedScan>& track,
                     const std::vector<eval::ReferenceCheck>& reference, double target_m,
                     double target_deg, const std::filesystem::path& path) {
  std::vector<double> times, meters, degrees, fit_m, fit_deg;
  const double t0 = track.empty() ? 0.0 : track.front().stamp;
  // Logs whose clock does not increase are drawn against the scan index.
  bool timed = true;
  for (std::size_t i = 1; i < track.size(); ++i)
    timed = timed && track[i].stamp >= track[i - 1].stamp;
  for (std::size_t i = 0; i < track.size(); ++i) {
    if (!track[i].estimated) continue;
    times.push_back(timed ? track[i].stamp - t0 : static_cast<double>(i));
    meters.push_back(track[i].error_m);
    degrees.push_back(track[i].error_deg);
    fit_m.push_back(i < reference.size() ? reference[i].fit_m : 0.0);
    fit_deg.push_back(i < reference.size() ? reference[i].fit_deg : 0.0);
  }
  const double t_end = times.empty() ? 1.0 : times.back();
  cv::Mat image(kTopPx + 2 * kPanelHeightPx + 2 * kGapPx, kWidthPx, CV_8UC3,
                cv::Scalar(255, 255, 255));
  cv::putText(image, title, {kLeftPx, 24}, cv::FONT_HERSHEY_SIMPLEX, 0.55, kAxisColor, 1,
              cv::LINE_AA);
  const Panel top(&image, kTopPx, t_end, Scale(meters, target_m));
  const Panel bottom(&image, kTopPx + kPanelHeightPx + kGapPx, t_end, Scale(degrees, target_deg));
  top.Curve(times, fit_m, kReferenceColor);
  top.Curve(times, meters, kErrorColor);
  top.Target(target_m);
  top.Axes("position error (m); grey: reference pose vs the scan's best fit in the map", 3);
  bottom.Curve(times, fit_deg, kReferenceColor);
  bottom.Curve(times, degrees, kErrorColor);
  bottom.Target(target_deg);
  bottom.Axes(std::string("heading error (deg) over ") + (timed ? "log seconds" : "scans"), 2);
  return drawing::WritePng(image, path);
}

}  // namespace semchain::app
