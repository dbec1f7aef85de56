#include "semantic/semantic_grid.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace semchain::semantic {

SemanticGrid::SemanticGrid(const GridGeometry& geometry, int class_count,
                           const SemanticGridOptions& options)
    : geometry_(geometry), options_(options) {
  for (int c = 0; c < class_count; ++c) {
    log_odds_.emplace_back(geometry.height, geometry.width, CV_32FC1, cv::Scalar(0));
    view_sum_.emplace_back(geometry.height, geometry.width, CV_32FC2, cv::Scalar(0, 0));
    point_sum_.emplace_back(geometry.height, geometry.width, CV_32FC3, cv::Scalar(0, 0, 0));
  }
}

void SemanticGrid::Add(cv::Mat& layer, const Eigen::Vector2i& cell, double delta) const {
  float& value = layer.at<float>(cell.y(), cell.x());
  value = static_cast<float>(
      std::clamp(value + delta, -options_.max_abs_log_odds, options_.max_abs_log_odds));
}

void SemanticGrid::Update(const FrameEvidence& evidence) {
  cv::Mat hit_this_frame(geometry_.height, geometry_.width, CV_8UC1, cv::Scalar(0));
  for (int c = 0; c < class_count() && c < static_cast<int>(evidence.hits.size()); ++c) {
    for (const CellHit& hit : evidence.hits[c]) {
      const Eigen::Vector2i& cell = hit.cell;
      if (!geometry_.Contains(cell)) continue;
      hit_this_frame.at<std::uint8_t>(cell.y(), cell.x()) = 1;
      Add(log_odds_[c], cell, options_.hit_log_odds);
      for (int other = 0; other < class_count(); ++other) {
        if (other != c) Add(log_odds_[other], cell, options_.miss_log_odds);
      }
      // Relative to the cell centre, so that float sums keep their precision.
      const Eigen::Vector2d offset = hit.mean_point - geometry_.CenterOf(cell);
      cv::Vec3f& points = point_sum_[c].at<cv::Vec3f>(cell.y(), cell.x());
      points[0] += static_cast<float>(offset.x());
      points[1] += static_cast<float>(offset.y());
      points[2] += 1.0f;
      Eigen::Vector2d toward = evidence.viewer - geometry_.CenterOf(cell);
      const double norm = toward.norm();
      if (norm > 1e-9) {
        toward /= norm;
        cv::Vec2f& sum = view_sum_[c].at<cv::Vec2f>(cell.y(), cell.x());
        sum[0] += static_cast<float>(toward.x());
        sum[1] += static_cast<float>(toward.y());
      }
    }
  }
  for (int c = 0; c < class_count() && c < static_cast<int>(evidence.undetected.size()); ++c) {
    for (const Eigen::Vector2i& cell : evidence.undetected[c]) {
      if (!geometry_.Contains(cell) || hit_this_frame.at<std::uint8_t>(cell.y(), cell.x()))
        continue;
      Add(log_odds_[c], cell, options_.undetected_log_odds);
    }
  }
  for (const Eigen::Vector2i& cell : evidence.free_cells) {
    if (!geometry_.Contains(cell) || hit_this_frame.at<std::uint8_t>(cell.y(), cell.x())) continue;
    for (cv::Mat& layer : log_odds_) Add(layer, cell, options_.miss_log_odds);
  }
}

double SemanticGrid::Probability(int c, const Eigen::Vector2i& cell) const {
  return 1.0 - 1.0 / (1.0 + std::exp(static_cast<double>(LogOdds(c, cell))));
}

Eigen::Vector2d SemanticGrid::ViewDirection(int c, const Eigen::Vector2i& cell) const {
  const cv::Vec2f sum = view_sum_[c].at<cv::Vec2f>(cell.y(), cell.x());
  const Eigen::Vector2d direction(sum[0], sum[1]);
  const double norm = direction.norm();
  return norm > 1e-9 ? Eigen::Vector2d(direction / norm) : Eigen::Vector2d::Zero();
}

Eigen::Vector2d SemanticGrid::MeanPoint(int c, const Eigen::Vector2i& cell) const {
  const cv::Vec3f sum = point_sum_[c].at<cv::Vec3f>(cell.y(), cell.x());
  const Eigen::Vector2d center = geometry_.CenterOf(cell);
  if (sum[2] <= 0.0f) return center;
  return center + Eigen::Vector2d(sum[0], sum[1]) / static_cast<double>(sum[2]);
}

int SemanticGrid::HitFrames(int c, const Eigen::Vector2i& cell) const {
  return static_cast<int>(point_sum_[c].at<cv::Vec3f>(cell.y(), cell.x())[2]);
}

std::vector<Eigen::Vector2i> CellsOnSegment(const GridGeometry& geometry,
                                            const Eigen::Vector2d& from,
                                            const Eigen::Vector2d& to) {
  std::vector<Eigen::Vector2i> cells;
  const Eigen::Vector2i a = geometry.CellOf(from);
  const Eigen::Vector2i b = geometry.CellOf(to);
  // cv::LineIterator clips the segment to the image; 8-connected like a Bresenham ray.
  cv::LineIterator it(cv::Size(geometry.width, geometry.height), cv::Point(a.x(), a.y()),
                      cv::Point(b.x(), b.y()), 8);
  cells.reserve(static_cast<std::size_t>(it.count));
  for (int i = 0; i < it.count; ++i, ++it) {
    const cv::Point p = it.pos();
    cells.emplace_back(p.x, p.y);
  }
  return cells;
}

}  // namespace semchain::semantic
