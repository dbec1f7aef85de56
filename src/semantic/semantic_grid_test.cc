#include "semantic/semantic_grid.h"

#include <gtest/gtest.h>

namespace semchain::semantic {
namespace {

const GridGeometry kGridGeometry{20, 10, 0.1, Eigen::Vector2d(0.0, 0.0)};

FrameEvidence Hit(int c, const Eigen::Vector2i& cell) {
  FrameEvidence evidence;
  evidence.hits.resize(3);
  evidence.hits[c].push_back({cell, kGridGeometry.CenterOf(cell) + Eigen::Vector2d(0.02, -0.01)});
  evidence.viewer = Eigen::Vector2d(0.0, 0.5);
  return evidence;
}

TEST(SemanticGridTest, RepeatedHitsRaiseAndMissesLower) {
  SemanticGrid grid(kGridGeometry, 3, SemanticGridOptions());
  const Eigen::Vector2i cell(5, 5);
  double last = grid.Probability(1, cell);
  EXPECT_DOUBLE_EQ(last, 0.5);
  for (int i = 0; i < 4; ++i) {
    grid.Update(Hit(1, cell));
    const double p = grid.Probability(1, cell);
    EXPECT_GT(p, last);  // eq. 2: each observation raises the posterior
    last = p;
  }
  EXPECT_NEAR(grid.LogOdds(1, cell), 4 * 0.847, 1e-5);
  // A hit of class 1 is evidence against the others there.
  EXPECT_LT(grid.Probability(0, cell), 0.5);
  EXPECT_EQ(grid.HitFrames(1, cell), 4);
  EXPECT_NEAR(grid.MeanPoint(1, cell).x(), kGridGeometry.CenterOf(cell).x() + 0.02, 1e-6);
  // The camera was to the west: the view direction points there.
  EXPECT_LT(grid.ViewDirection(1, cell).x(), -0.9);

  FrameEvidence free;
  free.free_cells = {cell};
  for (int i = 0; i < 3; ++i) {
    grid.Update(free);
    const double p = grid.Probability(1, cell);
    EXPECT_LT(p, last);
    last = p;
  }
  EXPECT_NEAR(grid.LogOdds(1, cell), 4 * 0.847 - 3 * 0.405, 1e-5);
}

TEST(SemanticGridTest, UndetectedSurfacesFadeAndValuesAreClamped) {
  SemanticGridOptions options;
  SemanticGrid grid(kGridGeometry, 3, options);
  const Eigen::Vector2i cell(2, 3);
  for (int i = 0; i < 50; ++i) grid.Update(Hit(2, cell));
  EXPECT_FLOAT_EQ(grid.LogOdds(2, cell), static_cast<float>(options.max_abs_log_odds));
  FrameEvidence seen;
  seen.undetected = {{}, {}, {cell}};
  grid.Update(seen);
  EXPECT_NEAR(grid.LogOdds(2, cell), options.max_abs_log_odds + options.undetected_log_odds, 1e-5);
  // A cell hit in the same frame is not also free or undetected.
  FrameEvidence both = Hit(2, cell);
  both.free_cells = {cell};
  both.undetected = {{}, {}, {cell}};
  const float before = grid.LogOdds(2, cell);
  grid.Update(both);
  EXPECT_GE(grid.LogOdds(2, cell), before);
}

// A segment's cells do not depend on the extent of the grid (it grows with the SLAM map).
TEST(SemanticGridTest, SegmentCellsAreNotClippedToTheGrid) {
  const std::vector<Eigen::Vector2i> cells =
      CellsOnSegment(kGridGeometry, Eigen::Vector2d(0.05, 0.05), Eigen::Vector2d(5.0, 0.05));
  ASSERT_EQ(cells.size(), 51u);  // the grid is 20 cells wide
  EXPECT_EQ(cells.front(), Eigen::Vector2i(0, 0));
  EXPECT_EQ(cells.back(), Eigen::Vector2i(50, 0));
}

// Grown, the grid keeps its cells' values and numbers, and a crop back to the first extent
// is the grid that never grew.
TEST(SemanticGridTest, GrowAndCropKeepTheCells) {
  SemanticGrid fixed(kGridGeometry, 3, SemanticGridOptions());
  SemanticGrid growing(kGridGeometry, 3, SemanticGridOptions());
  FrameEvidence evidence;
  evidence.hits = {{}, {{Eigen::Vector2i(4, 5), Eigen::Vector2d(0.23, 0.27)}}, {}};
  evidence.free_cells = {Eigen::Vector2i(6, 5), Eigen::Vector2i(-3, 2)};
  fixed.Update(evidence);
  growing.GrowToInclude(Eigen::Vector2i(-3, 2), Eigen::Vector2i(6, 5), 4);
  EXPECT_TRUE(growing.Contains(Eigen::Vector2i(-3, 2)));
  growing.Update(evidence);
  EXPECT_LT(growing.LogOdds(0, Eigen::Vector2i(-3, 2)), 0.0f);
  const SemanticGrid cropped = growing.Crop(kGridGeometry);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(cv::norm(cropped.log_odds(c), fixed.log_odds(c), cv::NORM_INF), 0.0);
  }
  EXPECT_EQ(cropped.MeanPoint(1, Eigen::Vector2i(4, 5)), fixed.MeanPoint(1, Eigen::Vector2i(4, 5)));
  // Clearing the cell forgets its evidence.
  cv::Mat mask = growing.MakeMask();
  growing.Mark(Eigen::Vector2i(4, 5), mask);
  growing.Clear(mask);
  EXPECT_EQ(growing.LogOdds(1, Eigen::Vector2i(4, 5)), 0.0f);
  EXPECT_EQ(growing.HitFrames(1, Eigen::Vector2i(4, 5)), 0);
}

}  // namespace
}  // namespace semchain::semantic
