#include "drawing/plots.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "drawing/pixels.h"

namespace semchain::drawing {

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

}  // namespace semchain::drawing
