#include "semantic/semantic_grid.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>

namespace semchain::semantic {

SemanticGrid::SemanticGrid(const GridGeometry& geometry, int class_count,
                           const SemanticGridOptions& options)
    : lattice_(geometry), geometry_(geometry), options_(options) {
  for (int c = 0; c < class_count; ++c) {
    log_odds_.emplace_back(geometry.height, geometry.width, CV_32FC1, cv::Scalar(0));
    view_sum_.emplace_back(geometry.height, geometry.width, CV_32FC2, cv::Scalar(0, 0));
    point_sum_.emplace_back(geometry.height, geometry.width, CV_32FC3, cv::Scalar(0, 0, 0));
  }
}

void SemanticGrid::Add(cv::Mat& layer, const Eigen::Vector2i& index, double delta) const {
  float& value = layer.at<float>(index.y(), index.x());
  value = static_cast<float>(
      std::clamp(value + delta, -options_.max_abs_log_odds, options_.max_abs_log_odds));
}

void SemanticGrid::Update(const FrameEvidence& evidence, const cv::Mat& mask) {
  // Storage index of a cell, or nothing outside the grid or the mask.
  const auto index_of = [&](const Eigen::Vector2i& cell) -> std::optional<Eigen::Vector2i> {
    const Eigen::Vector2i index = cell - anchor_;
    if (!geometry_.Contains(index)) return std::nullopt;
    if (!mask.empty() && mask.at<std::uint8_t>(index.y(), index.x()) == 0) return std::nullopt;
    return index;
  };
  cv::Mat hit_this_frame(geometry_.height, geometry_.width, CV_8UC1, cv::Scalar(0));
  for (int c = 0; c < class_count() && c < static_cast<int>(evidence.hits.size()); ++c) {
    for (const CellHit& hit : evidence.hits[c]) {
      const std::optional<Eigen::Vector2i> index = index_of(hit.cell);
      if (!index) continue;
      const int x = index->x();
      const int y = index->y();
      hit_this_frame.at<std::uint8_t>(y, x) = 1;
      Add(log_odds_[c], *index, options_.hit_log_odds);
      for (int other = 0; other < class_count(); ++other) {
        if (other != c) Add(log_odds_[other], *index, options_.miss_log_odds);
      }
      // Relative to the cell centre, so that float sums keep their precision.
      const Eigen::Vector2d center = lattice_.CenterOf(hit.cell);
      const Eigen::Vector2d offset = hit.mean_point - center;
      cv::Vec3f& points = point_sum_[c].at<cv::Vec3f>(y, x);
      points[0] += static_cast<float>(offset.x());
      points[1] += static_cast<float>(offset.y());
      points[2] += 1.0f;
      Eigen::Vector2d toward = evidence.viewer - center;
      const double norm = toward.norm();
      if (norm > 1e-9) {
        toward /= norm;
        cv::Vec2f& sum = view_sum_[c].at<cv::Vec2f>(y, x);
        sum[0] += static_cast<float>(toward.x());
        sum[1] += static_cast<float>(toward.y());
      }
    }
  }
  for (int c = 0; c < class_count() && c < static_cast<int>(evidence.undetected.size()); ++c) {
    for (const Eigen::Vector2i& cell : evidence.undetected[c]) {
      const std::optional<Eigen::Vector2i> index = index_of(cell);
      if (!index || hit_this_frame.at<std::uint8_t>(index->y(), index->x())) continue;
      Add(log_odds_[c], *index, options_.undetected_log_odds);
    }
  }
  for (const Eigen::Vector2i& cell : evidence.free_cells) {
    const std::optional<Eigen::Vector2i> index = index_of(cell);
    if (!index || hit_this_frame.at<std::uint8_t>(index->y(), index->x())) continue;
    for (cv::Mat& layer : log_odds_) Add(layer, *index, options_.miss_log_odds);
  }
}

void SemanticGrid::GrowToInclude(const Eigen::Vector2i& low, const Eigen::Vector2i& high,
                                 int margin) {
  Eigen::Vector2i new_low = anchor_;
  Eigen::Vector2i new_high = anchor_ + Eigen::Vector2i(geometry_.width, geometry_.height);
  for (int axis = 0; axis < 2; ++axis) {
    if (low[axis] < new_low[axis]) new_low[axis] = low[axis] - margin;
    if (high[axis] >= new_high[axis]) new_high[axis] = high[axis] + 1 + margin;
  }
  if (new_low == anchor_ &&
      new_high == anchor_ + Eigen::Vector2i(geometry_.width, geometry_.height)) {
    return;
  }
  GridGeometry grown = lattice_;
  grown.width = new_high.x() - new_low.x();
  grown.height = new_high.y() - new_low.y();
  grown.origin = lattice_.origin + new_low.cast<double>() * lattice_.resolution;
  const cv::Rect old_area(anchor_.x() - new_low.x(), anchor_.y() - new_low.y(), geometry_.width,
                          geometry_.height);
  const auto grow = [&](cv::Mat& layer) {
    cv::Mat bigger(grown.height, grown.width, layer.type(), cv::Scalar::all(0));
    if (!layer.empty()) layer.copyTo(bigger(old_area));
    layer = bigger;
  };
  for (std::size_t c = 0; c < log_odds_.size(); ++c) {
    grow(log_odds_[c]);
    grow(view_sum_[c]);
    grow(point_sum_[c]);
  }
  geometry_ = grown;
  anchor_ = new_low;
}

cv::Mat SemanticGrid::MakeMask() const {
  return cv::Mat(geometry_.height, geometry_.width, CV_8UC1, cv::Scalar(0));
}

void SemanticGrid::Mark(const Eigen::Vector2i& cell, cv::Mat& mask) const {
  const Eigen::Vector2i index = cell - anchor_;
  if (geometry_.Contains(index)) mask.at<std::uint8_t>(index.y(), index.x()) = 1;
}

void SemanticGrid::Clear(const cv::Mat& mask) {
  for (std::size_t c = 0; c < log_odds_.size(); ++c) {
    log_odds_[c].setTo(cv::Scalar::all(0), mask);
    view_sum_[c].setTo(cv::Scalar::all(0), mask);
    point_sum_[c].setTo(cv::Scalar::all(0), mask);
  }
}

Eigen::Vector2i SemanticGrid::LatticeOffsetOf(const GridGeometry& geometry) const {
  const Eigen::Vector2d cells = (geometry.origin - lattice_.origin) / lattice_.resolution;
  return {static_cast<int>(std::lround(cells.x())), static_cast<int>(std::lround(cells.y()))};
}

SemanticGrid SemanticGrid::Crop(const GridGeometry& geometry) const {
  SemanticGrid cropped(geometry, class_count(), options_);
  // The target's cell (0, 0) in this grid's storage.
  const Eigen::Vector2i start = LatticeOffsetOf(geometry) - anchor_;
  const cv::Rect source_area = cv::Rect(start.x(), start.y(), geometry.width, geometry.height) &
                               cv::Rect(0, 0, geometry_.width, geometry_.height);
  if (source_area.empty()) return cropped;
  const cv::Rect target_area(source_area.x - start.x(), source_area.y - start.y(),
                             source_area.width, source_area.height);
  for (std::size_t c = 0; c < log_odds_.size(); ++c) {
    log_odds_[c](source_area).copyTo(cropped.log_odds_[c](target_area));
    view_sum_[c](source_area).copyTo(cropped.view_sum_[c](target_area));
    point_sum_[c](source_area).copyTo(cropped.point_sum_[c](target_area));
  }
  return cropped;
}

double SemanticGrid::Probability(int c, const Eigen::Vector2i& cell) const {
  return 1.0 - 1.0 / (1.0 + std::exp(static_cast<double>(LogOdds(c, cell))));
}

Eigen::Vector2d SemanticGrid::ViewDirection(int c, const Eigen::Vector2i& cell) const {
  const cv::Vec2f sum = view_sum_[c].at<cv::Vec2f>(cell.y() - anchor_.y(), cell.x() - anchor_.x());
  const Eigen::Vector2d direction(sum[0], sum[1]);
  const double norm = direction.norm();
  return norm > 1e-9 ? Eigen::Vector2d(direction / norm) : Eigen::Vector2d::Zero();
}

Eigen::Vector2d SemanticGrid::MeanPoint(int c, const Eigen::Vector2i& cell) const {
  const cv::Vec3f sum = point_sum_[c].at<cv::Vec3f>(cell.y() - anchor_.y(), cell.x() - anchor_.x());
  const Eigen::Vector2d center = lattice_.CenterOf(cell);
  if (sum[2] <= 0.0f) return center;
  return center + Eigen::Vector2d(sum[0], sum[1]) / static_cast<double>(sum[2]);
}

int SemanticGrid::HitFrames(int c, const Eigen::Vector2i& cell) const {
  const Eigen::Vector2i index = cell - anchor_;
  return static_cast<int>(point_sum_[c].at<cv::Vec3f>(index.y(), index.x())[2]);
}

std::vector<Eigen::Vector2i> CellsOnSegment(const GridGeometry& geometry,
                                            const Eigen::Vector2d& from,
                                            const Eigen::Vector2d& to) {
  std::vector<Eigen::Vector2i> cells;
  const Eigen::Vector2i a = geometry.CellOf(from);
  const Eigen::Vector2i b = geometry.CellOf(to);
  // cv::LineIterator (8-connected, like a Bresenham ray) on an image that holds both ends, so
  // that nothing is clipped: the cells do not depend on the map's extent, which grows.
  const Eigen::Vector2i low = a.cwiseMin(b);
  const Eigen::Vector2i size = (a - b).cwiseAbs() + Eigen::Vector2i::Ones();
  cv::LineIterator it(cv::Size(size.x(), size.y()), cv::Point(a.x() - low.x(), a.y() - low.y()),
                      cv::Point(b.x() - low.x(), b.y() - low.y()), 8);
  cells.reserve(static_cast<std::size_t>(it.count));
  for (int i = 0; i < it.count; ++i, ++it) {
    const cv::Point p = it.pos();
    cells.emplace_back(p.x + low.x(), p.y + low.y());
  }
  return cells;
}

}  // namespace semchain::semantic
