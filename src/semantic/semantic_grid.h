#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "semantic/grid_geometry.h"
#include "semantic/semantic_options.h"

// The incremental Bayesian semantic grid of seed 001 eq. 1–2: one log-odds layer per class on
// the cells of the occupancy map. Every frame adds its evidence to the same cells, so a second
// pass over a place sharpens the objects already there instead of adding copies.
namespace semchain::semantic {

// What one camera frame says: per class the cells where its detections' points fell, and the
// cells the camera saw through.
struct CellHit {
  Eigen::Vector2i cell;
  Eigen::Vector2d mean_point;  // mean of the frame's points in the cell (map frame)
};

struct FrameEvidence {
  std::vector<std::vector<CellHit>> hits;   // per class, each cell once
  std::vector<Eigen::Vector2i> free_cells;  // each cell once
  // Per class, surface cells the camera saw without detecting that class there.
  std::vector<std::vector<Eigen::Vector2i>> undetected;
  Eigen::Vector2d viewer = Eigen::Vector2d::Zero();  // camera position (map frame)
};

// Cells are numbered on the lattice of the geometry the grid was made with ('cell' arguments
// below); the grid can grow beyond it (GrowToInclude) while the SLAM map grows, and every cell
// keeps its number. Each cell's value depends only on the evidence that touched that cell, in
// order, so a grid can be cut to any map on the same lattice (Crop) or rebuilt in part.
class SemanticGrid {
 public:
  SemanticGrid(const GridGeometry& geometry, int class_count, const SemanticGridOptions& options);

  // Eq. 2 in log-odds form: l += log p(class | z) / (1 − p(class | z)) per observation. A hit
  // of class c raises layer c and lowers the other layers at that cell (one object has one
  // class); a free cell lowers every layer; a surface seen where the detector reported no
  // object of class c lowers layer c a little (spurious detections fade when a place is seen
  // again). Cells outside the grid are ignored; with a non-empty 'mask' (MakeMask) only the
  // cells marked in it change.
  void Update(const FrameEvidence& evidence, const cv::Mat& mask = cv::Mat());

  // Extends the grid (in steps of 'margin' cells) so that it holds the cells from 'low' to
  // 'high'; the cells already there keep their values.
  void GrowToInclude(const Eigen::Vector2i& low, const Eigen::Vector2i& high, int margin);
  // A CV_8UC1 mask of the grid's extent, and a cell marked in it (ignored outside).
  cv::Mat MakeMask() const;
  void Mark(const Eigen::Vector2i& cell, cv::Mat& mask) const;
  // Forgets all evidence in the cells marked in 'mask'.
  void Clear(const cv::Mat& mask);
  // This grid on 'geometry' (same resolution, origin on this grid's lattice): the cells it
  // shares with this grid keep their values, the others are empty. Cells of the result are
  // numbered on 'geometry'.
  SemanticGrid Crop(const GridGeometry& geometry) const;
  // The cell of this grid's lattice at cell (0, 0) of 'geometry' (an origin on the lattice).
  Eigen::Vector2i LatticeOffsetOf(const GridGeometry& geometry) const;

  // The extent of the grid; equal to the geometry it was made with until it grows.
  const GridGeometry& geometry() const { return geometry_; }
  // The geometry the grid was made with: its lattice numbers the cells.
  const GridGeometry& lattice() const { return lattice_; }
  bool Contains(const Eigen::Vector2i& cell) const { return geometry_.Contains(cell - anchor_); }
  int class_count() const { return static_cast<int>(log_odds_.size()); }
  // CV_32FC1 log-odds of class 'c' over geometry(), row = cell y (of the lattice, until the
  // grid grows).
  const cv::Mat& log_odds(int c) const { return log_odds_[c]; }
  float LogOdds(int c, const Eigen::Vector2i& cell) const {
    return log_odds_[c].at<float>(cell.y() - anchor_.y(), cell.x() - anchor_.x());
  }
  double Probability(int c, const Eigen::Vector2i& cell) const;
  // The mean direction from the cell towards the cameras that saw class 'c' there (unit or
  // zero): the side the object was seen from.
  Eigen::Vector2d ViewDirection(int c, const Eigen::Vector2i& cell) const;
  // The mean of the points of class 'c' that fell in the cell (its centre when none did), for
  // sub-cell accuracy, and the number of frames that hit it.
  Eigen::Vector2d MeanPoint(int c, const Eigen::Vector2i& cell) const;
  int HitFrames(int c, const Eigen::Vector2i& cell) const;

 private:
  void Add(cv::Mat& layer, const Eigen::Vector2i& index, double delta) const;

  GridGeometry lattice_;
  GridGeometry geometry_;                             // the extent: lattice_ moved by anchor_ cells
  Eigen::Vector2i anchor_ = Eigen::Vector2i::Zero();  // the lattice cell at geometry_'s (0, 0)
  SemanticGridOptions options_;
  std::vector<cv::Mat> log_odds_;
  std::vector<cv::Mat> view_sum_;   // CV_32FC2 sums of unit vectors towards the camera
  std::vector<cv::Mat> point_sum_;  // CV_32FC3 sums of the frames' mean points and their count
};

// The cells on the straight segment from 'from' to 'to' (both in map coordinates), numbered on
// 'geometry' and not clipped to it: the same cells whatever the extent of the map.
std::vector<Eigen::Vector2i> CellsOnSegment(const GridGeometry& geometry,
                                            const Eigen::Vector2d& from, const Eigen::Vector2d& to);

}  // namespace semchain::semantic
